/* tiptap: the whole public API of libtiptap in one header.
 *
 *   #include <tiptap.h>      (pkg-config --cflags tiptap, or find_package(tiptap))
 *
 * Every public header, layer by layer from the bottom (docs/architecture.md); each can
 * also be included on its own. tests/lib_exports.sh checks that none is missing here.
 * docs/library.md shows a program built against the installed library. */
#ifndef TIPTAP_H
#define TIPTAP_H

#include "tiptap/export.h"
#include "tiptap/version.h"

#include "tiptap/util/cancel.h"
#include "tiptap/util/clock.h"
#include "tiptap/util/phase.h"
#include "tiptap/util/error.h"
#include "tiptap/util/str.h"
#include "tiptap/util/table.h"
#include "tiptap/util/warning.h"

#include "tiptap/io/decimate.h"
#include "tiptap/io/files.h"
#include "tiptap/io/gsf.h"
#include "tiptap/io/gwy.h"
#include "tiptap/io/height_image.h"
#include "tiptap/io/hdf5.h"
#include "tiptap/io/image.h"
#include "tiptap/io/lock.h"
#include "tiptap/io/outfile.h"
#include "tiptap/io/plot.h"

#include "tiptap/physics/cantilever.h"
#include "tiptap/physics/contact.h"
#include "tiptap/physics/material.h"

#include "tiptap/solver/averaged.h"
#include "tiptap/solver/envelope.h"
#include "tiptap/solver/graze.h"
#include "tiptap/solver/integrator.h"
#include "tiptap/solver/noise.h"
#include "tiptap/solver/shooting.h"

#include "tiptap/instrument/accuracy.h"
#include "tiptap/instrument/approach.h"
#include "tiptap/instrument/erosion.h"
#include "tiptap/instrument/feedback.h"
#include "tiptap/instrument/lockin.h"
#include "tiptap/instrument/piezo.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/instrument/scan_hdf5.h"
#include "tiptap/instrument/scan_envelope_stops.h"
#include "tiptap/instrument/scan_oscillation.h"
#include "tiptap/instrument/scan_scope.h"
#include "tiptap/instrument/scanner.h"
#include "tiptap/instrument/surface.h"
#include "tiptap/instrument/tip.h"
#include "tiptap/instrument/trace.h"

#include "tiptap/config/config.h"
#include "tiptap/config/ini.h"
#include "tiptap/config/meta.h"
#include "tiptap/config/read_force_tune.h"
#include "tiptap/config/read_trace.h"
#include "tiptap/config/scene.h"
#include "tiptap/config/setup.h"
#include "tiptap/config/solver_scene.h"
#include "tiptap/config/standard.h"
#include "tiptap/config/sweep.h"
#include "tiptap/config/units.h"

#include "tiptap/run/force.h"
#include "tiptap/run/force_volume.h"
#include "tiptap/run/run.h"
#include "tiptap/run/sweep.h"
#include "tiptap/run/tune.h"

#endif
