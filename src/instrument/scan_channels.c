/* The scan's channels: their names, units and harmonics, and a list of names parsed
 * into a mask (see include/tiptap/instrument/scan.h). */
#include "tiptap/instrument/scan.h"

#include <stdio.h>
#include <string.h>

enum { NHARM = TT_CH_HARMONIC_MAX - 1 }; /* harmonic channels of each kind */

static const struct {
    const char *name, *unit;
} channel_info[TT_CH_COUNT] = {
    {"height", "m"},     {"error", "m"},       {"phase", "deg"},       {"peak_force", "N"},
    {"indentation", "m"}, {"dissipation", "J"}, {"topography", "m"},   {"amplitude", "m"},
    {"harmonic2", "m"},  {"harmonic3", "m"},   {"harmonic4", "m"},     {"harmonic5", "m"},
    {"harmonic6", "m"},  {"harmonic7", "m"},   {"harmonic8", "m"},
    {"harmonic2_phase", "deg"}, {"harmonic3_phase", "deg"}, {"harmonic4_phase", "deg"},
    {"harmonic5_phase", "deg"}, {"harmonic6_phase", "deg"}, {"harmonic7_phase", "deg"},
    {"harmonic8_phase", "deg"}, {"artefact", "m"},
    {"dissipation_hysteresis", "J"}, {"dissipation_damping", "J"}, {"dissipation_viscous", "J"},
    {"dilation", "m"}, {"certainty", ""}, {"amplitude_2", "m"}, {"phase_2", "deg"},
};

const char *tt_scan_channel_name(int i) { return i >= 0 && i < TT_CH_COUNT ? channel_info[i].name : "?"; }
const char *tt_scan_channel_unit(int i) { return i >= 0 && i < TT_CH_COUNT ? channel_info[i].unit : "?"; }
int tt_scan_channel_count(void) { return TT_CH_COUNT; }

int tt_scan_channel_harmonic(int i)
{
    /* mode 2's lock-in outputs come per block too (the first harmonic of its drive) */
    if (i == 1 || i == 2 || i == 7 || i == TT_CH_AMPLITUDE2_INDEX || i == TT_CH_PHASE2_INDEX)
        return 1;
    if (i >= TT_CH_HARMONIC_INDEX && i < TT_CH_HARMONIC_INDEX + NHARM)
        return i - TT_CH_HARMONIC_INDEX + 2;
    if (i >= TT_CH_HARMONIC_PHASE_INDEX && i < TT_CH_HARMONIC_PHASE_INDEX + NHARM)
        return i - TT_CH_HARMONIC_PHASE_INDEX + 2;
    return 0;
}

int tt_scan_channels_parse(const char *text, unsigned *mask, char *why, size_t len)
{
    *mask = 0;
    const char *p = text;
    while (*p) {
        while (*p == ' ' || *p == ',' || *p == '\t')
            p++;
        if (!*p)
            break;
        const char *e = p;
        while (*e && *e != ',' && *e != ' ' && *e != '\t')
            e++;
        int found = -1;
        for (int i = 0; i < TT_CH_COUNT; i++)
            if (strlen(channel_info[i].name) == (size_t)(e - p) &&
                strncmp(channel_info[i].name, p, (size_t)(e - p)) == 0)
                found = i;
        if (found < 0) {
            snprintf(why, len,
                     "unknown channel '%.*s'; channels are height, error, amplitude, phase, "
                     "peak_force, indentation, dissipation, topography, harmonic2 to harmonic%d, "
                     "harmonic2_phase to harmonic%d_phase, artefact, dissipation_hysteresis, "
                     "dissipation_damping, dissipation_viscous, dilation, certainty, amplitude_2, phase_2",
                     (int)(e - p), p, TT_CH_HARMONIC_MAX, TT_CH_HARMONIC_MAX);
            return -1;
        }
        *mask |= 1u << found;
        p = e;
    }
    if (!*mask) {
        snprintf(why, len, "no channel named");
        return -1;
    }
    return 0;
}
