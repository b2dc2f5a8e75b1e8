#!/usr/bin/env bash
# cmake --install gives a usable library: into a prefix inside the build folder, the
# shared library, tiptap.h, tiptap.pc, the CMake package, the program, the Python
# package and the docs; the C example outside the tree (examples/c-api) builds against
# the installed library through pkg-config and through find_package(tiptap), and its
# numbers equal the installed program's for the same scene.
# usage: lib_install.sh build_dir source_dir sanitize(0|1) [python]
set -u
build=$1 src=$2 sanitize=${3:-0} python=${4:-}
source "$(dirname "$0")/tt_cli.sh"
prefix=$build/install-test
rm -rf "$prefix"
if cmake --install "$build" --prefix "$prefix" >"$tmp/install.log" 2>&1; then
  ok "cmake --install --prefix $prefix"
else
  bad "cmake --install: $(tail -3 "$tmp/install.log")"; exit 1
fi
libdir=$(dirname "$(find "$prefix" -name 'libtiptap.so.*.*.*' | head -1)")
for f in "$libdir/libtiptap.so" "$libdir/libtiptap_hdf5.so" "$prefix/include/tiptap.h" "$prefix/include/tiptap/version.h" \
         "$prefix/include/tiptap/instrument/scan.h" "$libdir/pkgconfig/tiptap.pc" \
         "$libdir/cmake/tiptap/tiptapConfig.cmake" "$libdir/cmake/tiptap/tiptapConfigVersion.cmake" \
         "$prefix/bin/tiptap" "$prefix/share/doc/tiptap/README.md" "$prefix/share/doc/tiptap/library.md"; do
  [ -e "$f" ] && ok "installed ${f#$prefix/}" || bad "not installed: ${f#$prefix/}"
done
init=$(find "$prefix" -path '*/tiptap/__init__.py' | head -1)
[ -n "$init" ] && ok "installed the Python package (${init#$prefix/})" || bad "no Python package under $prefix"
[ -z "$(find "$prefix" -name '*.a')" ] && ok "no static library installed" || bad "a static library installed"

version=$("$prefix/bin/tiptap" --version)
[ "$version" = "tiptap $(grep -o '"[0-9.]*"' "$prefix/include/tiptap/version.h" | tr -d '"')" ] &&
  ok "tiptap --version ($version) is TIPTAP_VERSION_STRING" || bad "tiptap --version: $version"
# the library a program loads, resolved
loads() { realpath "$(ldd "$1" | sed -n 's/.*libtiptap\.so[^ ]* => \([^ ]*\) .*/\1/p')" 2>/dev/null; }
installed=$(realpath "$libdir"/libtiptap.so.*.*.*)
# the installed program runs with the installed library (RUNPATH $ORIGIN/../lib)
[ "$(loads "$prefix/bin/tiptap")" = "$installed" ] && ok "the installed program loads the installed library" ||
  bad "installed program: $(ldd "$prefix/bin/tiptap" | grep tiptap)"

# the installed Python package finds the installed library by itself (under the
# sanitizers with their runtimes preloaded into the interpreter, as ctest's py_ tests do)
if [ -n "$python" ] && [ -n "$init" ]; then
  pyenv=()
  [ "$sanitize" = 1 ] && pyenv=(LD_PRELOAD="${TT_PY_PRELOAD:-}" ASAN_OPTIONS=detect_leaks=0)
  got=$(cd "$tmp" && env -u TIPTAP_LIBRARY "${pyenv[@]}" PYTHONPATH="$(dirname "$(dirname "$init")")" "$python" -c \
        'import os, tiptap, tiptap._lib as l; print(tiptap.version, os.path.realpath(l._library_path()))' 2>&1)
  [ "$got" = "${version#tiptap } $installed" ] &&
    ok "import tiptap loads the installed library" || bad "import tiptap: $got"
fi

# the example, copied out of the tree, built twice against the installed library
cp -r "$src/examples/c-api" "$tmp/example"
flags=""
[ "$sanitize" = 1 ] && flags="-fsanitize=address,undefined"
scene=("$src/examples/seed-fig4a/scene.ini" approach.points=40)
"$prefix/bin/tiptap" approach "${scene[0]}" --set "${scene[1]}" -o "$tmp/cli.csv" -q
cut -d, -f1-3 "$tmp/cli.csv" >"$tmp/want.csv"
check_run() { # name, binary
  if "$2" "${scene[@]}" >"$tmp/$1.out" 2>"$tmp/$1.err"; then
    head -1 "$tmp/$1.out" | grep -q "^# libtiptap $(echo "$version" | cut -d' ' -f2)" &&
      ok "$1: runs with the installed library's version" || bad "$1: $(head -1 "$tmp/$1.out")"
    sed 1d "$tmp/$1.out" >"$tmp/$1.csv"
    cmp -s "$tmp/$1.csv" "$tmp/want.csv" && ok "$1: the approach equals tiptap approach's CSV ($(($(wc -l <"$tmp/want.csv") - 1)) rows)" ||
      bad "$1: differs from tiptap approach: $(diff "$tmp/$1.csv" "$tmp/want.csv" | head -3)"
  else
    bad "$1 failed: $(head -3 "$tmp/$1.err")"
  fi
  [ "$(loads "$2")" = "$installed" ] && ok "$1: loads the installed library" || bad "$1: $(ldd "$2" | grep tiptap)"
}
if make -s -C "$tmp/example" PKG_CONFIG_PATH="$libdir/pkgconfig" CFLAGS="-O2 -Wall -Wextra -Werror $flags" \
     LDFLAGS="-Wl,-rpath,$libdir $flags" >"$tmp/make.log" 2>&1; then
  ok "the example builds through pkg-config"
  check_run pkg-config "$tmp/example/approach"
else
  bad "pkg-config build: $(tail -5 "$tmp/make.log")"
fi
if cmake -S "$tmp/example" -B "$tmp/example-build" -DCMAKE_PREFIX_PATH="$prefix" \
     -DCMAKE_C_FLAGS="-Wall -Werror $flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" >"$tmp/cmake.log" 2>&1 &&
   cmake --build "$tmp/example-build" >>"$tmp/cmake.log" 2>&1; then
  ok "the example builds through find_package(tiptap)"
  check_run find_package "$tmp/example-build/approach"
else
  bad "find_package build: $(tail -5 "$tmp/cmake.log")"
fi
# a version the package does not have is refused
mkdir -p "$tmp/v9"
cat >"$tmp/v9/CMakeLists.txt" <<'EOF'
cmake_minimum_required(VERSION 3.20)
project(v9 LANGUAGES C)
find_package(tiptap 9 REQUIRED)
EOF
cmake -S "$tmp/v9" -B "$tmp/v9/b" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null 2>&1 &&
  bad "find_package(tiptap 9) accepted version $version" || ok "find_package(tiptap 9) refused"
rm -rf "$prefix"
exit $fail
