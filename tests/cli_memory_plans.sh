#!/usr/bin/env bash
# The scan's printed memory estimate counts each thread's envelope plans, one per state
# dimension its materials take with their kept models (src/instrument/scan_worker.c,
# tt_scan_envelope_plans_bytes): with thermal noise the viscoelastic blend with an arm
# (examples/viscoelastic-blend/arms.ini, a second dimension) holds more than the blend
# without, by more than a plan's 3.5 MB, and the elastic blend's plan shows against the
# noiseless one's.
# usage: cli_memory_plans.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"
ex=$src/examples/viscoelastic-blend
small=(--set scan.lines=1 --set scan.profile_line=0 --set scan.pixels=8 --set solver.tier=envelope -j 1)
mb() { # the estimate's memory in MB from the scan's first line on stderr
  "$tiptap" scan "$src/scans/quick.ini" "$ex/scene.ini" "$@" "${small[@]}" -o "$tmp/out" 2>&1 |
    sed -n 's/.*, \([0-9.]*\) \([kMG]\)B of memory$/\1 \2/p' |
    awk '{ print $2 == "k" ? $1 / 1000 : $2 == "G" ? $1 * 1000 : $1 }'
}
quiet=$(mb --set "noise.temperature=0 K")
elastic=$(mb --set "noise.temperature=300 K")
arms=$(mb "$ex/arms.ini" --set "noise.temperature=300 K")
echo "estimates: noiseless $quiet MB, with noise $elastic MB, with the arm $arms MB"
[ -n "$quiet" ] && [ -n "$elastic" ] && [ -n "$arms" ] || { bad "no memory estimate printed"; exit 1; }
awk -v a="$elastic" -v b="$quiet" 'BEGIN { exit !(a >= b + 3.5) }' &&
  ok "the noisy plan's kept models counted ($elastic MB against $quiet MB)" ||
  bad "the noisy plan's kept models not counted ($elastic MB against $quiet MB)"
awk -v a="$arms" -v b="$elastic" 'BEGIN { exit !(a >= b + 3.5) }' &&
  ok "the arm's plan counted ($arms MB against $elastic MB)" ||
  bad "the arm's plan not counted ($arms MB against $elastic MB)"
exit $fail
