/* tiptap: the running library's version (tiptap/version.h). */
#include "tiptap/version.h"

const char *tt_version(void) { return TIPTAP_VERSION_STRING; }

int tt_version_number(void) { return TIPTAP_VERSION_NUMBER; }
