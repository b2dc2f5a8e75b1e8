/* Whether Gwyddion itself loads a file we wrote: its thumbnailer renders it, where it is
 * installed (CI installs it); skipped with a message otherwise. */
#ifndef TT_GWYDDION_TEST_H
#define TT_GWYDDION_TEST_H

#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tt_test.h"

static inline void tt_assert_gwyddion_loads(const char *path)
{
    static int told;
    if (system("command -v gwyddion-thumbnailer >/dev/null 2>&1") != 0) {
        if (!told++)
            print_message("gwyddion-thumbnailer not installed: Gwyddion load not checked\n");
        return;
    }
    char thumb[512], cmd[1200];
    snprintf(thumb, sizeof thumb, "%s.png", path);
    snprintf(cmd, sizeof cmd, "gwyddion-thumbnailer gnome2 64 '%s' '%s'", path, thumb);
    assert_int_equal(system(cmd), 0);
    struct stat sb;
    assert_int_equal(stat(thumb, &sb), 0); /* a thumbnail, not just an exit code */
    assert_true(sb.st_size > 0);
    unlink(thumb);
}

#endif
