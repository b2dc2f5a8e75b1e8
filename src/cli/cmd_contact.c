/* tiptap contact: placeholder until the contact module lands. */
#include "commands.h"

int cmd_contact(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    return cli_fail(1, "contact: not yet built");
}
