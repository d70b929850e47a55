#!/usr/bin/env bash
# Soak of the hovercraft physics (not in CI): runs `overflight sim` for STEPS
# steps (default 10 million) with random key presses, for several seeds, on
# the demo island and on every height map in ../shared/data/game/ (*_h.*),
# plus any TERRAIN given as an argument, and pipes each run through
# bench/soak_sim, which checks every step: finite numbers, inside the map,
# above every surface the renderers draw (DESIGN sec. 8).
#
#   bash scripts/soak_sim.sh [TERRAIN ...]
#   env: STEPS (10000000), SEEDS ("1 2 3 4"), PRESSES per run (400),
#        BUILD (build/release), DEMO_SIZE (1025)
#
# A run's presses come from bash's RANDOM seeded with the seed, so a failure
# is reproduced by running the same seed again (the command is printed).
set -euo pipefail
cd "$(dirname "$0")/.."

steps="${STEPS:-10000000}"
seeds="${SEEDS:-1 2 3 4}"
presses="${PRESSES:-400}"
build="${BUILD:-build/release}"
demo_size="${DEMO_SIZE:-1025}"
overflight="$build/apps/overflight"
checker="$build/bench/soak_sim"
for exe in "$overflight" "$checker"; do
  [ -x "$exe" ] || { echo "soak_sim.sh: $exe is missing (cmake --build $build --target overflight soak_sim)"; exit 1; }
done

terrains=(demo)
for f in ../shared/data/game/*_h.*; do
  [ -f "$f" ] && terrains+=("$f")
done
terrains+=("$@")

keys=(accelerate accelerate accelerate brake left right) # mostly moving
status=0
for terrain in "${terrains[@]}"; do
  for seed in $seeds; do
    RANDOM=$seed
    args=()
    for ((i = 0; i < presses; i++)); do
      # 30-bit uniform start; holds from 10 ms to 10 minutes.
      from=$(( ((RANDOM << 15) | RANDOM) % steps ))
      len=$(( 1 + ((RANDOM << 15) | RANDOM) % 60000 ))
      to=$(( from + len > steps ? steps : from + len ))
      [ "$to" -gt "$from" ] && args+=("${keys[RANDOM % ${#keys[@]}]}:$from-$to")
    done
    extra=()
    [ "$terrain" = demo ] && extra=(--demo-size "$demo_size")
    echo "== $terrain seed $seed: $overflight sim $terrain ${extra[*]} --steps $steps --press (${#args[@]} presses)"
    start=$SECONDS
    if ! "$overflight" sim "$terrain" "${extra[@]}" --steps "$steps" --press "${args[@]}" |
         "$checker" "$terrain" "${extra[@]}" --steps "$steps"; then
      echo "FAIL: $terrain seed $seed"
      status=1
    fi
    echo "   $((SECONDS - start)) s"
  done
done
[ "$status" = 0 ] && echo "soak_sim.sh: all runs passed"
exit "$status"
