#!/usr/bin/env bash
# tiptap sweep of points with mode 2 driven (bimodal AM-AM): steady and setpoint rows
# carry mode 2's lock-in (amplitude_2_nm, phase_2_deg) after the rest, found = settled
# (no Newton: the point settles its lock-ins); on the blend's disk at 16 nm mode 2 lags
# about 21 deg, as the bimodal scan reads there, and its amplitude scales with its drive
# (0.090 and 0.182 nm for 0.25 and 0.5 nm free); a one-mode sweep has no such columns.
# usage: cli_sweep_bimodal.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"
cd "$tmp" || exit 1
base=("$src/scans/standard.ini" "$src/surfaces/polymer-blend.ini" --set approach.material=disk
      --set "approach.from=16 nm")

"$tiptap" sweep "${base[@]}" --set cantilever.modes=2 \
  --vary "cantilever.mode2_free_amplitude=0.25 nm,0.5 nm" --run steady -j 2 -q -o st.csv 2>st.err ||
  bad "steady sweep: $(cat st.err)"
head -1 st.csv | grep -q ',period,found,amplitude_2_nm,phase_2_deg$' && ok "mode 2's columns last" ||
  bad "header: $(head -1 st.csv)"
# columns from the end: phase_2, amplitude_2, found
awk -F, 'NR > 1 { print $(NF - 2), $(NF - 1), $NF }' st.csv >rows
awk '$1 != "settled" {bad = 1} END {exit bad || NR != 2}' rows && ok "found = settled" ||
  bad "found: $(cat rows)"
awk '$3 < 18 || $3 > 24 {bad = 1} END {exit bad}' rows && ok "mode 2 lags about 21 deg on the disk" ||
  bad "phase_2: $(cat rows)"
awk 'NR == 1 {a = $2} NR == 2 {r = $2 / a} END {exit !(r > 1.9 && r < 2.1)}' rows &&
  ok "mode 2's amplitude twice for twice the drive" || bad "amplitude_2: $(cat rows)"

"$tiptap" sweep "${base[@]}" --set cantilever.modes=2 --set "cantilever.mode2_free_amplitude=0.5 nm" \
  --vary "feedback.setpoint=80%" --run setpoint -j 1 -q -o sp.csv 2>sp.err || bad "setpoint sweep: $(cat sp.err)"
head -1 sp.csv | grep -q ',amplitude_2_nm,phase_2_deg$' && ok "setpoint sweep: mode 2's columns" ||
  bad "setpoint header: $(head -1 sp.csv)"
awk -F, 'NR == 2 { exit !($NF > 15 && $NF < 25 && $(NF - 1) > 0.1 && $(NF - 1) < 0.25) }' sp.csv &&
  ok "at the 16 nm setpoint: mode 2 below 0.25 nm, about 20 deg" || bad "setpoint row: $(sed -n 2p sp.csv)"

"$tiptap" sweep "${base[@]}" --vary "cantilever.free_amplitude=20 nm" --run steady -j 1 -q -o one.csv \
  2>one.err || bad "one-mode sweep: $(cat one.err)"
head -1 one.csv | grep -q 'amplitude_2' && bad "one mode: mode 2's columns" || ok "one mode: none"
exit $fail
