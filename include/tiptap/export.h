/* tiptap: what the shared library exports.
 *
 * The library is compiled with -fvisibility=hidden: a function is exported only when
 * it is declared in a public header between TT_BEGIN_DECLS and TT_END_DECLS, which
 * every header under include/tiptap/ wraps its declarations in (they also give C++ its
 * extern "C"). Everything else, the helpers of src/ included, stays inside the library.
 * tests/lib_exports.sh checks both ways: each function declared in include/tiptap is
 * exported, and nothing else is.
 *
 *   #include "tiptap/export.h"
 *   TT_BEGIN_DECLS
 *   int tt_example(int x);
 *   TT_END_DECLS
 *
 * TT_API marks one declaration outside such a block.
 */
#ifndef TIPTAP_EXPORT_H
#define TIPTAP_EXPORT_H

#if defined(__GNUC__) || defined(__clang__)
#define TT_API __attribute__((visibility("default")))
#define TT_VISIBILITY_PUSH _Pragma("GCC visibility push(default)")
#define TT_VISIBILITY_POP _Pragma("GCC visibility pop")
#else
#define TT_API
#define TT_VISIBILITY_PUSH
#define TT_VISIBILITY_POP
#endif

#ifdef __cplusplus
#define TT_BEGIN_DECLS TT_VISIBILITY_PUSH extern "C" {
#define TT_END_DECLS } TT_VISIBILITY_POP
#else
#define TT_BEGIN_DECLS TT_VISIBILITY_PUSH
#define TT_END_DECLS TT_VISIBILITY_POP
#endif

#endif
