#!/usr/bin/env bash
# The shared library exports its public API and nothing else (include/tiptap/export.h):
# every function declared in a header under include/tiptap/ is a dynamic symbol of
# libtiptap.so, and every dynamic symbol it defines is declared there. A header whose
# declarations are not wrapped in TT_BEGIN_DECLS / TT_END_DECLS, or a helper of src/
# that leaks out, fails here by name. Also: each header compiles on its own, as C and as
# C++, and the umbrella header tiptap.h includes every one.
# usage: lib_exports.sh path/to/libtiptap.so source_dir binary_dir
set -u
lib=$1 src=$2 bin=$3
source "$(dirname "$0")/tt_cli.sh"
inc=(-I "$src/include" -I "$bin/include")

# (include/tiptap/live/ is tiptap live's console, a part of the program over this API,
# not of the library: left out here, from tiptap.h and from cmake --install)
mapfile -t headers < <(cd "$src/include" && find tiptap -name '*.h' -not -path 'tiptap/live/*' | sort; \
                       cd "$bin/include" && find tiptap -name '*.h' | sort)
[ ${#headers[@]} -gt 30 ] && ok "${#headers[@]} public headers" || bad "only ${#headers[@]} public headers found"

# each header on its own, as C11 and as C++ (the declarations' extern "C" block)
alone=0
for h in "${headers[@]}"; do
  printf '#include "%s"\n#include "%s"\n' "$h" "$h" >"$tmp/one.c"
  gcc -std=c11 -Wall -Wextra -Werror -fsyntax-only "${inc[@]}" "$tmp/one.c" 2>"$tmp/err" ||
    { bad "$h does not compile on its own: $(head -3 "$tmp/err")"; alone=1; }
done
[ $alone -eq 0 ] && ok "every header compiles on its own (and twice)"
if command -v g++ >/dev/null; then
  printf '#include "tiptap.h"\nint main() { return tt_version_number() > 0 ? 0 : 1; }\n' >"$tmp/cxx.cc"
  g++ -Wall -Werror -fsyntax-only "${inc[@]}" "$tmp/cxx.cc" 2>"$tmp/err" &&
    ok "tiptap.h compiles as C++" || bad "tiptap.h as C++: $(head -3 "$tmp/err")"
fi

# the umbrella header names every header
missing=""
for h in "${headers[@]}"; do
  grep -qF "#include \"$h\"" "$src/include/tiptap.h" || missing="$missing $h"
done
[ -z "$missing" ] && ok "tiptap.h includes every public header" || bad "tiptap.h lacks:$missing"

# the functions the headers declare, as the compiler reads them (-aux-info lists every
# prototype with the file and line that declared it)
for h in "${headers[@]}"; do printf '#include "%s"\n' "$h"; done >"$tmp/all.c"
gcc -std=c11 -fsyntax-only -aux-info "$tmp/aux" "${inc[@]}" "$tmp/all.c" 2>"$tmp/err" ||
  bad "headers: $(head -3 "$tmp/err")"
grep -E "^/\* ($src|$bin)/include/tiptap/" "$tmp/aux" |
  sed -E 's/^\/\* ([^:]*):.*\*\/ *(.*)$/\1 \2/' |
  sed -E 's/^([^ ]*) .*[ *](tt_[A-Za-z0-9_]+) *\(.*$/\2 \1/' | sort -u >"$tmp/declared_where"
cut -d' ' -f1 "$tmp/declared_where" | sort -u >"$tmp/declared"
n=$(wc -l <"$tmp/declared")
[ "$n" -gt 200 ] && ok "$n functions declared in the public headers" || bad "only $n declarations read"

# (OpenMP's named critical sections are global locks, .gomp_critical_user_NAME, shared
# by every object that names the section: the compiler makes them, not the API)
nm -D --defined-only "$lib" | awk '$2 ~ /^[TtWwDdBbRrVvIi]$/ {print $3}' | sed 's/@.*//' |
  grep -v '^\.gomp_critical_user_' | sort -u >"$tmp/exported"
[ -s "$tmp/exported" ] || bad "no dynamic symbols in $lib"

unexported=$(comm -23 "$tmp/declared" "$tmp/exported")
if [ -z "$unexported" ]; then
  ok "every declared function is exported"
else
  bad "declared in a public header but not exported (outside TT_BEGIN_DECLS, or not defined):"
  for f in $unexported; do grep "^$f " "$tmp/declared_where"; done
fi
leaked=$(comm -13 "$tmp/declared" "$tmp/exported")
if [ -z "$leaked" ]; then
  ok "nothing else is exported ($(wc -l <"$tmp/exported") symbols)"
else
  bad "exported but declared in no public header: $(echo $leaked)"
fi

# the library carries its SONAME, and the program links it
soname=$(readelf -d "$lib" | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p')
[[ "$soname" =~ ^libtiptap\.so\.[0-9]+$ ]] && ok "SONAME $soname" || bad "SONAME '$soname'"
exit $fail
