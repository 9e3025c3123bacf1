#!/usr/bin/env bash
# Regenerates the measured tables of README.md and docs/ (the files below): each block between
#   <!-- BEGIN name -->  and  <!-- END name -->
# is replaced by the output of the command registered for `name` below. With arguments,
# only the named blocks (e.g. `bash scripts/readme-tables.sh knife`). With `--check`
# first, the named blocks are regenerated and compared with the documents instead (no
# file is written) by scripts/compare-blocks.py, which leaves out timings (time columns,
# durations, speed ratios) and lets a number move by two units of its last printed
# digit: a difference is printed and fails (the test suite checks the blocks that take
# under a minute; harness/tests/readme_blocks.rs, ignored, the long ones).
set -euo pipefail
cd "$(dirname "$0")/.."
declare -A commands=(
  [accuracy_table]="cargo run --release -q --example accuracy_table"
  [seed_cases]="cargo run --release -q --example seed_cases"
  [knife]="cargo run --release -q -p jointlin-harness --bin jointlin -- loss scenes/knife.toml --out harness/assets/knife --quiet"
  [knife_graded_mesh]="cargo run --release -q -p jointlin-harness --bin jointlin -- loss scenes/knife.toml --mesh-study 1,2 --refine x:jaw_,blade_in --refine x:bar_ --refine y --refine z --sampled-only --out harness/assets/knife-graded-mesh --quiet"
  [knife_effects]="cargo run --release -q -p jointlin-harness --bin jointlin -- loss scenes/knife-coarse.toml --effects 12,15 --set iteration.mode=harmonic_balance --set iteration.harmonics=3 --set 'interfaces.*.rule=masing' --out harness/assets/knife-effects --quiet"
  [knife_graded_effects]="cargo run --release -q -p jointlin-harness --bin jointlin -- loss scenes/knife.toml --effects 12,15 --set 'interfaces.*.rule=masing' --out harness/assets/knife-graded-effects --quiet"
  [knife_modal]="cargo run --release -q -p jointlin-harness --example loss_bench"
  [knife_mesh]="cargo run --release -q -p jointlin-harness --bin jointlin -- loss scenes/knife-coarse.toml --mesh-study 1,2,3 --out harness/assets/knife-mesh --quiet"
  [tradeoff_beams]="cargo run --release -q -p jointlin-harness --bin jointlin -- tradeoff scenes/three-beams-coarse.toml --out out/tradeoff-beams"
  [tradeoff_block]="cargo run --release -q -p jointlin-harness --bin jointlin -- tradeoff scenes/block-stick.toml --out out/tradeoff-block"
  [tradeoff_oblique]="cargo run --release -q -p jointlin-harness --bin jointlin -- tradeoff scenes/three-beams-oblique.toml --out out/tradeoff-oblique"
  [tradeoff_oblique_coupled]="cargo run --release -q -p jointlin-harness --bin jointlin -- tradeoff scenes/three-beams-oblique.toml --set effects.coupled_slip=true --out out/tradeoff-oblique-coupled"
  [tradeoff_oblique_normal]="cargo run --release -q -p jointlin-harness --bin jointlin -- tradeoff scenes/three-beams-oblique.toml --set effects.normal_load_variation=true --out out/tradeoff-oblique-normal"
  [tradeoff_mass_on_plane]="cargo run --release -q -p jointlin-harness --bin jointlin -- tradeoff scenes/mass-on-plane.toml --out out/tradeoff-mass-on-plane"
  [tradeoff_oblique_both]="cargo run --release -q -p jointlin-harness --bin jointlin -- tradeoff scenes/three-beams-oblique.toml --set effects.coupled_slip=true --set effects.normal_load_variation=true --out out/tradeoff-oblique-both"
  [backbone_plot]="cargo run --release -q -p jointlin-harness --bin jointlin -- backbone scenes/jenkins-chain.toml --out harness/assets/backbone-chain --quiet 2>&1"
  [backbone_chain_h7]="cargo run --release -q -p jointlin-harness --bin jointlin -- backbone scenes/jenkins-chain.toml --harmonics 7 --amplitudes 0.02,20,300 --out harness/assets/backbone-chain-h7 --quiet 2>&1"
  [backbone_braced]="cargo run --release -q -p jointlin-harness --bin jointlin -- backbone scenes/mass-on-plane-braced.toml --harmonics 7 --out harness/assets/backbone-braced --quiet 2>&1"
  [backbone_cost]="cargo run --release -q -p jointlin-harness --bin jointlin -- mhb --backbones --scene scenes/three-beams-coarse.toml,scenes/three-beams.toml"
  [contact_effects]="cargo run --release -q -p jointlin-harness --bin jointlin -- effects scenes/three-beams-oblique.toml --out harness/assets/contact-effects"
  [backbone_fe]="cargo run --release -q -p jointlin-harness --bin jointlin -- backbone scenes/three-beams-coarse.toml --out harness/assets/backbone-three-beams --quiet 2>&1"
  [backbone_fe_h7]="cargo run --release -q -p jointlin-harness --bin jointlin -- backbone scenes/three-beams-coarse.toml --harmonics 7 --amplitudes 3e-6,3e-2,25 --out harness/assets/backbone-three-beams-h7 --quiet 2>&1"
  [three_beams_frf]="cargo run --release -q -p jointlin-harness --bin jointlin -- run scenes/three-beams.toml --out out/three-beams --quiet"
  [duffing_frf]="cargo run --release -q -p jointlin-harness --bin jointlin -- run scenes/duffing.toml --out out/duffing --quiet"
  [bolted_lap_frf]="cargo run --release -q -p jointlin-harness --bin jointlin -- run scenes/bolted-lap.toml --out out/bolted-lap --quiet"
  [deck_stack]="cargo run --release -q -p jointlin-harness --example deck_stack"
  [deck_bench]="cargo run --release -q -p jointlin-harness --example deck_bench"
  [modes_bench]="cargo run --release -q -p jointlin-harness --example modes_bench"
  [sweep_bench]="cargo run --release -q -p jointlin-harness --example sweep_bench"
  [modal_deck_bench]="cargo run --release -q -p jointlin-harness --example modal_deck_bench"
  [box_bench]="OPENBLAS_NUM_THREADS=1 cargo run --release -q -p jointlin-harness --bin jointlin -- bench --modal-box --dofs 100000 --freqs 100"
  [reduce_bench]="cargo run --release -q -p jointlin-harness --example reduce_bench"
  [deck_keywords]="cargo run --release -q -p jointlin-harness --bin jointlin -- check --keywords"
  [python_cost]="bash scripts/python-bench.sh"
  [python_study]="bash scripts/python.sh python/examples/study.py out/python-study"
)
# Plots a block's command writes that the documents show: "from to" pairs, several
# separated by ";"; a "from" may be a glob matching one file (a name with the peak's
# frequency in it). A name with a
# plot and no block in the documents (e.g. three_beams_frf) only makes its plot.
declare -A plots=(
  [tradeoff_beams]="out/tradeoff-beams/tradeoff.svg docs/accuracy-three-beams.svg"
  [tradeoff_block]="out/tradeoff-block/tradeoff.svg docs/accuracy-block.svg"
  [tradeoff_oblique]="out/tradeoff-oblique/tradeoff.svg docs/accuracy-oblique.svg"
  [tradeoff_oblique_both]="out/tradeoff-oblique-both/tradeoff.svg docs/accuracy-oblique-both.svg"
  [three_beams_frf]="out/three-beams/frf.svg harness/assets/three-beams-frf.svg"
  [duffing_frf]="out/duffing/frf.svg harness/assets/duffing-frf.svg"
  [python_study]="out/python-study/study.svg docs/python-study.svg"
  [bolted_lap_frf]="out/bolted-lap/frf.svg harness/assets/bolted-lap-frf.svg; out/bolted-lap/contact_ratio_*.svg harness/assets/bolted-lap-contact-ratio.svg; out/bolted-lap/contact_energy_*.svg harness/assets/bolted-lap-contact-energy.svg"
)
# Blocks whose command may stop part way and say so (exit status 1 with what it reached
# written): the block shows the message and the exit status instead of ending the script.
may_stop=" backbone_fe_h7 "
# Blocks whose command prints Markdown (the others are shown as terminal output).
markdown=" python_cost contact_effects accuracy_table knife knife_modal knife_graded_mesh knife_effects knife_graded_effects knife_mesh tradeoff_beams tradeoff_block tradeoff_oblique tradeoff_oblique_coupled tradeoff_oblique_normal tradeoff_oblique_both tradeoff_mass_on_plane backbone_cost deck_stack deck_bench modes_bench sweep_bench modal_deck_bench box_bench reduce_bench deck_keywords "
files=(README.md docs/abaqus.md docs/c-fortran.md docs/harness.md docs/own-model.md
  docs/thesis-cases.md docs/balance-and-backbones.md docs/cost.md docs/accuracy.md docs/python.md)
# Copies each "from to" pair of a plots entry; a glob must match exactly one file.
copy_plots() {
  local pair from to matches
  IFS=';' read -ra pairs <<< "$1"
  for pair in "${pairs[@]}"; do
    read -r from to <<< "$pair"
    # shellcheck disable=SC2206
    matches=($from)
    if [ ${#matches[@]} -ne 1 ] || [ ! -f "${matches[0]}" ]; then
      echo "error: $from matches ${#matches[@]} files, not one" >&2
      exit 1
    fi
    cp "${matches[0]}" "$to"
  done
}
check=0
if [ "${1:-}" = "--check" ]; then
  check=1
  shift
  [ $# -gt 0 ] || { echo "--check needs the blocks to check" >&2; exit 2; }
fi
names=("$@")
[ ${#names[@]} -gt 0 ] || names=("${!commands[@]}")
stale=0
for name in "${names[@]}"; do
  [ -n "${commands[$name]:-}" ] || { echo "unknown block: $name" >&2; exit 2; }
  targets=()
  for f in "${files[@]}"; do
    if grep -q "<!-- BEGIN $name -->" "$f"; then targets+=("$f"); fi
  done
  if [ ${#targets[@]} -eq 0 ]; then
    [ "$check" = 0 ] || { echo "no block $name in ${files[*]} to check" >&2; exit 2; }
    [ -n "${plots[$name]:-}" ] || continue
    echo "== $name (plot only): ${commands[$name]}"
    eval "${commands[$name]}" > /dev/null
    copy_plots "${plots[$name]}"
    continue
  fi
  echo "== $name: ${commands[$name]}"
  # A check leaves the command's output directory as it was (its run.json has a time
  # stamp): kept aside and put back.
  kept=""
  out_dir=$(sed -n 's/.*--out \([^ ]*\).*/\1/p' <<< "${commands[$name]}")
  if [ "$check" = 1 ] && [ -n "$out_dir" ] && [ -d "$out_dir" ]; then
    kept=$(mktemp -d)
    cp -a "$out_dir/." "$kept/"
  fi
  out=$(mktemp)
  if [[ "$markdown" == *" $name "* ]]; then
    { echo "Produced by \`${commands[$name]}\`:"; echo; eval "${commands[$name]}"; } > "$out"
  else
    if [[ "$may_stop" == *" $name "* ]]; then
      { echo '```text'; echo "\$ ${commands[$name]}"; eval "${commands[$name]}" || echo "(exit status $?)"; echo '```'; } > "$out"
    else
      { echo '```text'; echo "\$ ${commands[$name]}"; eval "${commands[$name]}"; echo '```'; } > "$out"
    fi
  fi
  for f in "${targets[@]}"; do
    if [ "$check" = 1 ]; then
      written=$(mktemp)
      perl -0ne "print \$1 if /<!-- BEGIN $name -->\n(.*?)<!-- END $name -->/s" "$f" > "$written"
      if ! python3 scripts/compare-blocks.py "$written" "$out" "$f ($name)"; then
        stale=1
      fi
      rm -f "$written"
      continue
    fi
    perl -0pi -e "my \$t = do { local \$/; open my \$f, '<', '$out' or die; <\$f> }; s/(<!-- BEGIN $name -->\n).*?(<!-- END $name -->)/\$1\$t\$2/s" "$f"
  done
  rm -f "$out"
  if [ -n "$kept" ]; then
    rm -rf "$out_dir"
    mkdir -p "$out_dir"
    cp -a "$kept/." "$out_dir/"
    rm -rf "$kept"
  fi
  [ "$check" = 0 ] || continue
  if [ -n "${plots[$name]:-}" ]; then
    copy_plots "${plots[$name]}"
  fi
done
if [ "$stale" = 1 ]; then
  echo "error: the blocks above differ from their commands' output: run bash scripts/readme-tables.sh NAME" >&2
  exit 1
fi
