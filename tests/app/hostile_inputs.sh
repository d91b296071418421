#!/bin/bash
# Hostile but realistic inputs through the dtwire executable (issues 20 and 37): each case must
# exit 2 before any work, naming the file (and line) or option and the closest known name where
# one exists; a run whose own physics check fails exits 1 with its partial results marked failed.
# Prints the count of cases that behave as the input contract says (docs/reference.md).
# Usage: hostile_inputs.sh <dtwire> <source dir> <scratch dir>
set -u
dtwire=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
prm=$src/experiments/default/sw_tension.prm
fit=$src/experiments/sw_fe_fit/macro_fit.toml

# Files the cases read.
sed 's/set Diameter (mm)/set Diamter (mm)/' "$prm" > typo_entry.prm
sed 's/set Young modulus (MPa)/set Youngs modulus (MPa)/' "$prm" > typo_young.prm
sed 's/^subsection Geometry/subsection Geometri/' "$prm" > typo_subsection.prm
: > empty.prm
printf '# only a comment\n\n' > comment_only.prm
sed 's/set Poisson ratio *=.*/set Poisson ratio = 0.5/' "$prm" > poisson_half.prm
sed 's/set Young modulus (MPa) *=.*/set Young modulus (MPa) = 0/' "$prm" > young_zero.prm
sed 's/set Length (mm) *=.*/set Length (mm) = 0/' "$prm" > length_zero.prm
sed 's/set Diameter (mm) *=.*/set Diameter (mm) = 0/' "$prm" > diameter_zero.prm
printf 'subsection Geometry\n  set Length (mm) = 60\n' > unclosed.prm
printf 'subsection Geometry\n  Length (mm) = 60\nend\n' > no_set.prm
printf 'end\n' > stray_end.prm
printf 'set arm-length = 30\n' > arm_length_segment.prm
echo "garbage" > garbage.msh
: > empty.msh
printf '$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\nxx\n' > broken.msh
for m in garbage empty broken; do
  printf 'subsection Geometry\n  set Cross section = full\n  set Mesh file = %s.msh\nend\n' $m > mesh_$m.prm
done

thesis=$src/experiments/data/macroelement_thesis_params.json
export_set() {  # export_set <python statement on the single_wire set s> <file>
  python3 -c "import json, sys
s = json.load(open('$thesis'))['single_wire']
exec(sys.argv[1])
json.dump({'single_wire': s}, open(sys.argv[2], 'w'))" "$1" "$2"
}
export_set "s['EA_N'] = -1" ea_negative.json
export_set "del s['EA_N']" ea_missing.json
export_set "s['Nult_N'] = 100" nult_below_n0.json
export_set "s['reference_length_m'] = 0" length_zero.json
python3 -c "import json; print(json.dumps({'single_wire': json.load(open('$thesis'))['single_wire']}).replace('16000000.0', '1e999'))" > overflow.json
python3 -c "import json; s = json.load(open('$thesis'))['single_wire']; s['slideb'] = s.pop('slide_b')
print('{\n  \"single_wire\":'); print(json.dumps(s, indent=2)); print('}')" > slideb.json
sed 's/^name = "m_f"$/name = "m_ff"/' "$fit" > m_ff.toml
sed 's|^fixed_parameters_section = "single_wire"$|fixed_parameters_section = "single_wire"\nfixed = {slideb = 0}|' "$fit" > fixed_typo.toml
# Nult fitted as the reserve Nult - N0 (offset_from): a misspelled base, a cycle, a reserve reference < 0.
sed 's/^offset_from = "N0_N"$/offset_from = "NO_N"/' "$fit" > offset_typo.toml
sed 's/^name = "N0_N"$/name = "N0_N"\noffset_from = "Nult_N"/' "$fit" > offset_cycle.toml
sed 's/^reference = 450$/reference = -50/' "$fit" > reserve_negative.toml
sed -i 's|"\.\./data/|"'"$src"'/experiments/data/|' m_ff.toml fixed_typo.toml offset_typo.toml offset_cycle.toml reserve_negative.toml
mkdir -p foreign && echo "my notes" > foreign/notes.txt
: > empty_mesh.prm
sed 's/^set twist-length/set twist-lenght/' "$src/experiments/default/dt_mesh.prm" > typo_mesh.prm

pass=0 total=0
# case <expected text in the output> <dtwire arguments...>
case_() {
  local expected=$1; shift
  total=$((total + 1))
  local output code
  output=$("$dtwire" "$@" 2>&1); code=$?
  if [ $code -eq 2 ] && [[ "$output" == *"$expected"* ]]; then
    pass=$((pass + 1))
  else
    echo "FAIL: dtwire $* -> exit $code, expected 2 and '$expected':"
    echo "$output" | head -5
  fi
}
out="-o $work/out -q"
case_ "typo_entry.prm:13: unknown entry 'Diamter (mm)' in subsection 'Geometry' (did you mean 'Diameter (mm)'?)" run typo_entry.prm $out
case_ "did you mean 'Young modulus (MPa)'" run typo_young.prm $out
case_ "typo_subsection.prm:" run typo_subsection.prm $out
case_ "did you mean 'Geometry'" run typo_subsection.prm $out
case_ "empty.prm: no 'set' line" run empty.prm $out
case_ "comment_only.prm: no 'set' line" run comment_only.prm $out
case_ "poisson_half.prm:24: subsection Material: 'Poisson ratio': expected a ratio in (-1, 0.5)" run poisson_half.prm $out
case_ "young_zero.prm:23: subsection Material: 'Young modulus (MPa)': expected a modulus > 0" run young_zero.prm $out
case_ "length_zero.prm:14: subsection Geometry: 'Length (mm)': expected a length > 0" run length_zero.prm $out
case_ "diameter_zero.prm:13: subsection Geometry: 'Diameter (mm)'" run diameter_zero.prm $out
case_ "unclosed.prm:1: subsection 'Geometry' is not closed" run unclosed.prm $out  # the line that opens it
case_ "no_set.prm:2: expected 'set Entry = value'" run no_set.prm $out
case_ "stray_end.prm:1: 'end' without a subsection" run stray_end.prm $out
case_ "mesh_garbage.prm:3: subsection Geometry: 'Mesh file'" run mesh_garbage.prm $out
case_ "empty.msh is empty or is not one" run mesh_empty.prm $out
case_ "broken.msh: cannot read the mesh" run mesh_broken.prm $out
case_ "--set: Material/Poisson ratio: 'Poisson ratio': expected a ratio" run "$prm" --set 'Material/Poisson ratio=0.5' $out
case_ "--set: Newton/Relative tolerance" run "$prm" --set 'Newton/Relative tolerance=0' $out
case_ "--set: 'Geometry/Diamter (mm)=3': unknown entry 'Geometry/Diamter (mm)' (did you mean 'Geometry/Diameter (mm)'?)" run "$prm" --set 'Geometry/Diamter (mm)=3' $out
case_ "--restart: Value -5 not in range" run "$prm" --restart -5 $out
# --threads is an alias of --jobs; CLI11 names the option by its first long name.
case_ "Value -1 not in range 1 to 1024" fit "$fit" --threads -1 -o "$work/fit"
case_ "Value 0 not in range 1 to 1024" fit "$fit" --threads 0 -o "$work/fit"
case_ "--trials: Value -1 not in range" gap selfcheck --trials -1
case_ "--backbone: no such file" gap selfcheck --trials 1 --backbone /nonexistent/backbone.csv
case_ "--write-curves: '$src/README.md' is a file" gap selfcheck --trials 1 --write-curves "$src/README.md"
case_ "--write-curves: '$src/tests' is not empty" gap selfcheck --trials 1 --write-curves "$src/tests"
case_ "--effects: 'bogus' is no curve-mode effect" gap selfcheck --trials 1 --effects gauge_length,bogus
case_ "--pair-trials: pairs need at least two --effects" gap selfcheck --trials 1 --effects gauge_length
case_ "--force-at-fraction: expected a number in [0, 0.99], got 1.5" gap mesh-selfcheck --model "$src/experiments/dem/gap_selfcheck_punch.toml" --force-at-fraction 1.5
# CLI::Range lets NaN through (every comparison with it is false).
case_ "--force-at-fraction: expected a finite number in [0, 0.99], got 'nan'" gap mesh-selfcheck --model "$src/experiments/dem/gap_selfcheck_punch.toml" --force-at-fraction nan
case_ "a mesh-test effect: it acts on a DEM panel model" gap features --model "$src/experiments/dt/dt_tension.prm" --effects mesh_distortion --json "$work/features.json"
case_ "--lab-peak: '5000': expected PEAK_N:SD_N" gap features --model "$src/experiments/dt/dt_tension.prm" --lab-peak 5000 --json "$work/features.json"
case_ "--lab-peak: '5000:-1': the peak and its standard deviation must be positive" gap features --model "$src/experiments/dt/dt_tension.prm" --lab-peak 5000:-1 --json "$work/features.json"
case_ "--model-set: 'Material/Failure locs' is no entry of the FE solver" gap features --model "$src/experiments/dt/dt_tension.prm" --model-set 'Material/Failure locs=johnson-cook' --json "$work/features.json"
case_ "junction_fracture: the .prm already carries a Hosford-Coulomb locus" gap features --model "$src/experiments/dt/dt_tension.prm" --effects junction_fracture --json "$work/features.json"
case_ "--steps" export --params "$src/experiments/data/macroelement_thesis_params.json" --steps 0 --out "$work/export"
case_ "no_such.prm" run no_such.prm $out
case_ "ea_negative.json: wire type 'single_wire' (law thesis): thesis: parameter 'EA_N' must be finite and > 0" export --params ea_negative.json --out export
case_ "ea_missing.json: wire type 'single_wire' (law thesis): thesis: missing parameter 'EA_N'" export --params ea_missing.json --out export
case_ "nult_below_n0.json: wire type 'single_wire' (law thesis): thesis: Nult_N must be >= N0_N" export --params nult_below_n0.json --out export
case_ "length_zero.json: wire type 'single_wire': 'reference_length_m': expected a length > 0" export --params length_zero.json --out export
case_ "overflow.json: not valid JSON" export --params overflow.json --out export
case_ "wire type 'single_wire' is also in ea_missing.json (one set per wire type" export --params ea_missing.json --params ea_negative.json --out export
case_ "no wire type 'gabion'; choose one of: double_twist, single_wire" export --params "$thesis#gabion" --out export
case_ "no wire type 'dt' in the --params files; choose one of: double_twist, single_wire" export --params "$thesis" --params "$thesis" --wire-type dt --out export
case_ "slideb.json:22: wire type 'single_wire': unknown parameter 'slideb' for law thesis (did you mean 'slide_b'?)" export --params slideb.json --out export
case_ "did you mean 'slide_b'" dem driver --law thesis --params slideb.json --out driver
case_ "slideb.json:22: wire type 'single_wire': unknown parameter 'slideb'" dem run "$src/experiments/dem/punch_macro.toml" --set-params sw=slideb.json -o dem_out -q
case_ "--set: boundary.support: expected pinned, hinged or slider" dem run "$src/experiments/dem/punch_macro.toml" --set 'boundary.support="rollers"' -o dem_out -q
case_ "--set: boundary.support: the value is not TOML" dem run "$src/experiments/dem/punch_macro.toml" --set 'boundary.support=slider' -o dem_out -q
case_ "boundary.presag_m: given with pretension_strain" dem run "$src/experiments/dem/punch_macro.toml" --set 'boundary.presag_m=0.01' -o dem_out -q
case_ "links.sw.parameters.slideb: not a parameter of the thesis law" dem run "$src/experiments/dem/punch_macro.toml" --set 'links.sw.parameters.slideb=1.0' -o dem_out -q
case_ "empty_mesh.prm: no 'set <name> = <value>' line" mesh dt --prm empty_mesh.prm -o mesh.msh
case_ "typo_mesh.prm:7:5: unknown parameter 'twist-lenght' (did you mean 'twist-length'?)" mesh dt --prm typo_mesh.prm -o mesh.msh
case_ "--length: expected an axis length between the twists > its two bends" mesh segment --length 8 -o segment.msh
case_ "parameter 'arm-length' is not used by mesh segment" mesh segment --prm arm_length_segment.prm -o segment.msh
[ -e segment.msh ] && { echo "FAIL: a refused segment mesh left its output"; total=$((total + 1)); }
case_ "parameter[6].name': the thesis simulator reads no parameter 'm_ff' (did you mean 'm_f'?)" fit m_ff.toml --synthesize synthesized
case_ "simulator.fixed.slideb': the thesis law reads no parameter 'slideb' (did you mean 'slide_b'?)" fit fixed_typo.toml --synthesize synthesized
case_ "offset_typo.toml:62:15: field 'parameter[4].offset_from': 'NO_N' names no other [[parameter]] of this file (did you mean 'N0_N'?)" fit offset_typo.toml --synthesize synthesized
case_ "offset_cycle.toml:49:15: field 'parameter[3].offset_from': parameter 'N0_N': offset_from closes a cycle (N0_N -> Nult_N -> N0_N)" fit offset_cycle.toml --synthesize synthesized
case_ "reserve_negative.toml:67:13: field 'parameter[4].reference': expected the reference of the offset Nult_N - N0_N, within [lower, upper]" fit reserve_negative.toml --synthesize synthesized
# --experiments names an experiment of the file, once each.
case_ "no experiment 'bendin' in the file (it has: tension" fit "$fit" --experiments tension,bendin --synthesize synthesized
case_ "--experiments: 'tension' is named twice" fit "$fit" --experiments tension,tension --synthesize synthesized
case_ "foreign: holds 'notes.txt', which this command does not write" export --params "$thesis" --out foreign
case_ ".: is the working directory or holds it" export --params "$thesis" --out .
[ -e "$work/synthesized" ] && { echo "FAIL: a refused fit left $work/synthesized"; total=$((total + 1)); }
[ "$(cat foreign/notes.txt)" = "my notes" ] || { echo "FAIL: a refused export touched foreign/notes.txt"; total=$((total + 1)); }
[ -e "$work/export" ] && { echo "FAIL: a refused export left $work/export"; total=$((total + 1)); }
[ -e "$work/out/curve.csv" ] && { echo "FAIL: a refused run left $work/out/curve.csv"; total=$((total + 1)); }
# DEM run inputs out of their physical range (issue 37), named with file:line or --set.
punch=$src/experiments/dem/punch_macro.toml
sed -e 's|"\.\./data/|"'"$src"'/experiments/data/|' -e 's/^friction = 0.2$/friction = -0.2/' "$punch" > negative_friction.toml
sed -e 's|"\.\./data/|"'"$src"'/experiments/data/|' -e 's/^frames = 15$/frames = -1/' "$punch" > frames_negative.toml
# The line the error must name is where the edited key is, wherever the input puts it.
friction_line=$(grep -n '^friction = -0.2$' negative_friction.toml | cut -d: -f1)
frames_line=$(grep -n '^frames = -1$' frames_negative.toml | cut -d: -f1)
case_ "negative_friction.toml:$friction_line:12: tool.friction: expected a Coulomb coefficient >= 0" dem run negative_friction.toml -o dem_out -q
case_ "frames_negative.toml:$frames_line:10: output.frames: expected an integer in [0, 100000]" dem run frames_negative.toml -o dem_out -q
case_ "--set: output.frames: expected an integer in [0, 100000]" dem run "$punch" --set output.frames=2.5 -o dem_out -q
case_ "--set: dynamics.threads: expected an integer in [1, 256]" dem run "$punch" --set dynamics.threads=1.5 -o dem_out -q
case_ "--set: dynamics.gravity_m_per_s2: expected an acceleration >= 0" dem run "$punch" --set dynamics.gravity_m_per_s2=-9.81 -o dem_out -q
case_ "--set: dynamics.settle_s: expected a time >= 0 s" dem run "$punch" --set dynamics.settle_s=-1 -o dem_out -q
case_ "--set: mesh.node_mass_kg: expected a mass >= 0 kg" dem run "$punch" --set mesh.node_mass_kg=-0.01 -o dem_out -q
case_ "--set: tool.duration_s: expected a time >= 0 s" dem run "$punch" --set tool.duration_s=-1 -o dem_out -q
case_ "--set: tool.unload_force_N: expected a force below the smallest of force_levels_N" dem run "$punch" --set 'tool.force_levels_N=[3000.0]' --set tool.unload_force_N=5000 -o dem_out -q
case_ "--set: tool.corner_plane_m: expected a distance in (side_m / 2, 3 side_m / 2]" dem run "$src/experiments/dem/impact.toml" --set tool.corner_plane_m=0.1 -o dem_out -q
case_ "--set: mesh.width_m: the panel is narrower than one mesh opening" dem run "$src/experiments/dem/strip_tension_thesis.toml" --set mesh.width_m=0.05 -o dem_out -q
case_ "--set: checks.max_balance_error_percent: expected a percentage >= 0" dem run "$punch" --set checks.max_balance_error_percent=-1 -o dem_out -q
case_ "--set: checks.max_energy_error: unknown key" dem run "$punch" --set checks.max_energy_error=1 -o dem_out -q
case_ "--set: mesh.nodes_per_wire: expected an integer in [2, 3]" dem run "$punch" --set mesh.nodes_per_wire=4 -o dem_out -q
case_ "--set: mesh.nodes_per_wire: expected an integer in [2, 3]" dem run "$punch" --set mesh.nodes_per_wire=2.5 -o dem_out -q
case_ "--set: mesh.nodes_per_wire: 3 needs links with bending stiffness" dem run "$src/experiments/dem/punch_wirepm.toml" --set mesh.nodes_per_wire=3 -o dem_out -q
case_ "mesh.nodes_per_wire: the YADE export needs 2" dem run "$punch" --set mesh.nodes_per_wire=3 --yade-script yade.py -o dem_out -q
# Resources: a 2000 x 2000 m panel is refused by its memory estimate in a moment, before anything
# is built; --max-memory lowers the limit; VTU frames beyond the free disk are refused.
start=$(date +%s)
case_ "punch_macro.toml: needs about " dem run "$punch" --set mesh.width_m=2000 --set mesh.height_m=2000 -o dem_out -q
# (20 s on a loaded machine; building that panel would take its memory, not seconds)
[ $(( $(date +%s) - start )) -le 20 ] || { echo "FAIL: the 2000 x 2000 m refusal took more than 20 s"; total=$((total + 1)); }
case_ "above --max-memory 1 MB; nothing was run" dem run "$punch" --max-memory 1M -o dem_out -q
case_ "--max-memory: expected a positive size such as 4G" dem run "$punch" --max-memory lots -o dem_out -q
case_ "(--no-frames writes none)" dem run "$punch" --set mesh.width_m=20 --set mesh.height_m=20 --set output.frames=100000 -o dem_out -q
[ -e "$work/dem_out" ] && { echo "FAIL: a refused dem run left $work/dem_out"; total=$((total + 1)); }
case_ "mesh: needs about " mesh sw --length 1e7 --level 3 -o big.msh  # 10 km typed for 10 mm
case_ "--steps: needs about " dem driver --law thesis --steps 100000000 --out driver_big
[ -e big.msh ] || [ -e driver_big ] && { echo "FAIL: a refused mesh or driver left its output"; total=$((total + 1)); }
# The FE run estimates its memory from the .prm (cells of the generated mesh, or counted in the
# mesh file) before building anything: ten million axial cells are a typo, refused in a moment.
start=$(date +%s)
case_ "needs about " run "$prm" --set 'Geometry/Axial cells=10000000' -o fe_big -q
# (20 s: MPI and PETSc start first, slow on a loaded machine; building the mesh would take hours)
[ $(( $(date +%s) - start )) -le 20 ] || { echo "FAIL: the 10^7-cell FE refusal took more than 20 s"; total=$((total + 1)); }
case_ "above --max-memory 10 MB; nothing was run" run "$prm" --max-memory 10M -o fe_big -q
case_ "--max-memory: expected a positive size such as 4G" run "$prm" --max-memory lots -o fe_big -q
[ -e fe_big ] && { echo "FAIL: a refused FE run left fe_big"; total=$((total + 1)); }
# A run whose physics check fails: exit 1 naming the check, the time and the bound; the partial
# curve stays and summary.json says "failed". A small, short punch with a bound no run can meet.
small=(--set mesh.width_m=0.6 --set mesh.height_m=0.6 --set dynamics.settle_s=0.5 --set tool.travel_m=0.06
       --set tool.speed_m_per_s=0.1 --set output.interval_s=0.05 --no-frames -q)
case_failed() {  # case_failed <expected text> <folder> <dtwire arguments...>
  local expected=$1 folder=$2; shift 2
  total=$((total + 1))
  local output code
  output=$("$dtwire" "$@" -o "$folder" 2>&1); code=$?
  if [ $code -eq 1 ] && [[ "$output" == *"$expected"* ]] && grep -q '"status": "failed"' "$folder/summary.json" &&
     [ -s "$folder/curve.csv" ] && grep -q "status: failed" "$folder/curve.csv"; then
    pass=$((pass + 1))
  else
    echo "FAIL: dtwire $* -> exit $code, expected 1, '$expected' and a partial result marked failed:"
    echo "$output" | head -5
  fi
}
case_failed "check 'energy_balance' failed at t = " balance dem run "$punch" "${small[@]}" --set checks.max_balance_error_percent=1e-9
case_failed "above the bound 0 % (checks.max_kinetic_share_percent)" kinetic dem run "$punch" "${small[@]}" --set checks.max_kinetic_share_percent=0
case_failed "check 'energy_balance' failed" strip dem run "$src/experiments/dem/strip_tension_thesis.toml" --set mesh.width_m=0.3 \
  --set mesh.height_m=0.4 --set tool.clamp_depth_m=0.05 --set tool.travel_m=0.004 --set output.interval_s=0.05 --no-frames -q \
  --set checks.max_balance_error_percent=1e-9
# An FE run whose contact penetrates deeper than its bound (here 0: any penetration): exit 1
# naming the check, the step and the bound; the steps before it stay in curve.partial.csv, marked
# failed, and summary.json says "failed". The default three-point bending: it stops at the step
# where the tool first touches the wire.
total=$((total + 1))
bend=$src/experiments/default/sw_bending.prm
output=$("$dtwire" run "$bend" --set 'Output/Fields=false' -q --set 'Checks/Max penetration (% of diameter)=0' \
         -o fe_penetration 2>&1); code=$?
if [ $code -eq 1 ] && [[ "$output" == *"check 'penetration' failed at step "* ]] &&
   [[ "$output" == *"(Checks/Max penetration (% of diameter))"* ]] && grep -q '"status": "failed"' fe_penetration/summary.json &&
   grep -q "status: failed" fe_penetration/curve.partial.csv && [ ! -e fe_penetration/curve.csv ]; then
  pass=$((pass + 1))
else
  echo "FAIL: an FE run beyond its penetration bound -> exit $code:"; echo "$output" | head -5
fi
fe_short=(--set 'Boundary conditions/Load path (mm)=0:0, 1:1' --set 'Output/Fields=false' -q)
# A short pull of the default wire within the default bounds: exit 0, "status": "ok".
total=$((total + 1))
if "$dtwire" run "$prm" "${fe_short[@]}" -o fe_ok > /dev/null 2>&1 && grep -q '"status": "ok"' fe_ok/summary.json &&
   grep -q "status: ok" fe_ok/curve.csv; then
  pass=$((pass + 1))
else
  echo "FAIL: a short FE pull within the default bounds did not end with status ok"
fi
case_ "--set: 'Checks/Max penetration (% of diameter)=-1'" run "$prm" --set 'Checks/Max penetration (% of diameter)=-1' $out
# The same small punch within the default bounds: exit 0 and "status": "ok".
total=$((total + 1))
if "$dtwire" dem run "$punch" "${small[@]}" -o ok > /dev/null 2>&1 && grep -q '"status": "ok"' ok/summary.json; then
  pass=$((pass + 1))
else
  echo "FAIL: a small punch within the default bounds did not end with status ok"
fi
# An interrupted run into a folder of an earlier run: the earlier results are gone and run.log
# says how to resume.
mkdir -p interrupted && touch interrupted/curve.csv interrupted/results.h5
"$dtwire" run "$prm" -o interrupted -q & pid=$!
# The interruption is meant for a running solve: wait for the run's first log line (its SIGINT
# handler is set right after it; a background job of a script starts with SIGINT ignored, so a
# signal before that is lost on a loaded machine), at most 120 s.
for _ in $(seq 600); do grep -q "^dtwire " interrupted/run.log 2> /dev/null && break; sleep 0.2; done
sleep 0.5; kill -INT $pid; wait $pid
total=$((total + 1))
if [ ! -e interrupted/curve.csv ] && [ ! -e interrupted/results.h5 ] && grep -q "interrupted (SIGINT); resume with: dtwire run" interrupted/run.log; then
  pass=$((pass + 1))
else
  echo "FAIL: SIGINT into a folder of an earlier run:"; ls interrupted; tail -2 interrupted/run.log
fi
# An export into the folder of an earlier export: only this export's sets remain, with one run id.
total=$((total + 1))
"$dtwire" export --params "$thesis" --out again > /dev/null &&
  "$dtwire" export --params "$thesis" --wire-type single_wire --out again > /dev/null
if [ -e again/single_wire_parameters.json ] && [ ! -e again/double_twist_parameters.json ] &&
   [ "$(grep -h -o '"run_id": "[^"]*"' again/*.json | sort -u | wc -l)" = 1 ] &&
   grep -q "# run_id: " again/single_wire_parameters.csv && ! ls -a . | grep -q '\.tmp\.'; then
  pass=$((pass + 1))
else
  echo "FAIL: export over an earlier export:"; ls -a again .
fi
# A laboratory curve with shuffled rows: diagnosed, but flagged on stderr and in the JSON.
total=$((total + 1))
python3 -c "import math, random
rows = [(0.03 * i / 199, 3000 * math.sin(3 * i / 199)) for i in range(200)]
open('sim.csv', 'w').write('displacement_m,force_N\n' + ''.join(f'{u},{0.9 * f}\n' for u, f in rows))
random.seed(3); random.shuffle(rows)
open('shuffled.csv', 'w').write('displacement_m,force_N\n' + ''.join(f'{u},{f}\n' for u, f in rows))"
if "$dtwire" gap --lab shuffled.csv --sim sim.csv --mode tension --json gap.json --report gap.md 2> gap.err > /dev/null &&
   grep -q "warning: shuffled.csv: the displacement reverses" gap.err && grep -q '"input_warnings"' gap.json; then
  pass=$((pass + 1))
else
  echo "FAIL: shuffled laboratory rows not flagged:"; cat gap.err | head -5
fi
# A compression curve against a tension simulation, a force in kN labelled N, a summary figure in
# kN given in N: diagnosed, but flagged on stderr and in the JSON (each curve is oriented by its
# own sign).
total=$((total + 1))
python3 -c "import math
rows = [(0.03 * i / 199, 3000 * math.sin(3 * i / 199)) for i in range(200)]
open('compression.csv', 'w').write('displacement_m,force_N\n' + ''.join(f'{-u},{-0.95 * f}\n' for u, f in rows))
open('kilonewtons.csv', 'w').write('displacement_m,force_N\n' + ''.join(f'{u},{0.95e-3 * f}\n' for u, f in rows))"
if "$dtwire" gap --lab compression.csv --sim sim.csv --json compression.json 2> compression.err > /dev/null &&
   grep -q "warning: compression.csv against the simulation sim.csv: the laboratory's force is mostly negative" compression.err &&
   grep -q '"input_warnings"' compression.json &&
   "$dtwire" gap --lab kilonewtons.csv --sim sim.csv --json kilonewtons.json 2> kilonewtons.err > /dev/null &&
   grep -q "(a column in kN labelled N?)" kilonewtons.err &&
   "$dtwire" gap --lab-summary peak_force_N=2.7:0.1 --sim sim.csv --mode tension --json summary_kn.json 2> summary_kn.err > /dev/null &&
   grep -q "a figure in kN given in N?" summary_kn.err && grep -q '"input_warnings"' summary_kn.json; then
  pass=$((pass + 1))
else
  echo "FAIL: a compression curve against tension, or kN as N, not flagged:"; cat compression.err kilonewtons.err summary_kn.err | head -5
fi
# Summary figures: a force at a negative displacement, and one beyond the simulated travel (30 mm).
case_ "unknown feature 'force_at_-420mm_N'" gap --lab-summary force_at_-420mm_N=1:1 --sim sim.csv --mode tension
case_ "force_at_45mm_N: the simulated curve reaches only 30" gap --lab-summary force_at_45mm_N=2000:100 --sim sim.csv --mode tension --json beyond.json
total=$((total + 1))
if [ ! -e beyond.json ]; then pass=$((pass + 1)); else echo "FAIL: beyond.json written by a refused diagnosis"; fi
# Careless numbers and paths (a helper's sweep, 2026-12-03): each refused before any work.
case_ "--noise: expected a finite number in [0, 1], got 'nan'" fit "$fit" --synthesize synth --noise nan
case_ "--seed: expected a whole number >= 0 (digits only), got '-1'" fit "$fit" --synthesize synth --seed -1
case_ "--max-strain: expected a finite number in [0, inf), got 'nan'" dem driver --law thesis --params "$thesis" --max-strain nan --out driver
case_ "--gauge-mm: expected a number in (0, inf), got -1" gap --lab sim.csv --sim sim.csv --gauge-mm -1 --area-mm2 5
case_ "--lab-peak-sd: expected a number in (0, inf), got 0" gap features --model "$src/experiments/dt/dt_tension.prm" --lab-curve sim.csv --lab-peak-sd 0
case_ "--d: expected a finite number, got inf" mesh sw --level 0 --d inf -o inf.msh
case_ "--arm-length: expected a finite number, got inf" mesh dt --level 0 --arm-length inf -o inf.msh
: > a_file
case_ "-o: '$work/a_file' is a file, not a folder" dem run "$src/experiments/dem/strip_tension_thesis.toml" -o a_file -q
case_ "-o: '$work/a_file' is a file, not a folder" fit "$fit" -o a_file
case_ "--json: '$work/a_file' is a file, not a folder" gap --lab sim.csv --sim sim.csv --mode tension --json a_file/x.json
case_ "--json: '$work' is a folder: expected a file name" gap --lab sim.csv --sim sim.csv --mode tension --json "$work"
case_ "--plot: 'gap.txt': expected a figure file ending in .png" gap --lab sim.csv --sim sim.csv --mode tension --plot gap.txt
case_ "--plot: 'strip.txt': expected a figure file ending in .png" dem run "$src/experiments/dem/strip_tension_thesis.toml" --plot strip.txt -o plot_out -q
case_ "-o: '$work/a_file' is a file, not a folder" run "$prm" -o a_file -q
python3 -c "import json; s = json.load(open('$thesis')); s['single_wire'] = [1, 2]; json.dump(s, open('array_set.json', 'w'))"
case_ "array_set.json: field 'single_wire': expected an object {name: value}" export --params array_set.json --out export
mkdir -p empty_campaign
case_ "--report-only: no step of campaign 'default' has its outputs in" campaign --report-only -o empty_campaign
printf '\xef\xbb\xbf' | cat - "$prm" > bom.prm
case_ "bom.prm:1:1: the file starts with a UTF-8 byte-order mark" run bom.prm $out
sed -e 's/^increments_per_leg = .*/increments_per_leg = 2000000000/' -e "s|\"\\.\\./|\"$src/experiments/|" "$fit" > huge_increments.toml
case_ "increments_per_leg': the path's" fit huge_increments.toml --synthesize synth_huge
# A plot that cannot be drawn (a binary without its scripts: an empty data folder) is refused
# before any run, not after the tables are written.
mkdir -p no_data
export DTWIRE_DATA_DIR=$work/no_data
case_ "band.png (dem propagate draws it; --no-plot skips it): the plot script $work/no_data/scripts/plot_band.py is missing" dem propagate "$src/experiments/dem/strip_tension_thesis.toml" --params-fit "sw=$thesis" -o band_out
case_ "--plot: the plot script $work/no_data/scripts/plot_curves.py is missing" run "$prm" --plot sw.png $out
case_ "--plot: the plot script" dem run "$src/experiments/dem/strip_tension_thesis.toml" --plot strip.png -o plot_out -q
case_ "--plot: the plot script" gap --lab sim.csv --sim sim.csv --mode tension --plot gap.png
unset DTWIRE_DATA_DIR
total=$((total + 1))
if [ ! -e band_out ] && [ ! -e plot_out ]; then pass=$((pass + 1)); else echo "FAIL: a refused plot left an output folder"; fi
echo "hostile inputs: $pass of $total cases refused as the input contract says"
[ $pass -eq $total ]
