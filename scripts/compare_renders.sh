#!/usr/bin/env bash
# Renders the same set of views with two `overflight` binaries and compares
# every output file byte for byte (PNG color and --depth TIFF):
#   bash scripts/compare_renders.sh OLD_BINARY NEW_BINARY OUT_DIR
# writes OUT_DIR/before/ (OLD) and OUT_DIR/after/ (NEW) and prints one line
# per view: "identical NAME" or "DIFFERENT NAME (color|depth|failed)". Exit
# status 1 when any view differs or fails. Real data from
# OVERFLIGHT_DATA (default /work/shared/data); views of missing files are left out.
set -uo pipefail

if [ $# -ne 3 ]; then
  echo "usage: $0 OLD_BINARY NEW_BINARY OUT_DIR" >&2
  exit 2
fi
old=$1 new=$2 out=$3
data=${OVERFLIGHT_DATA:-/work/shared/data}
for bin in "$old" "$new"; do
  [ -x "$bin" ] || { echo "$0: $bin: not an executable" >&2; exit 2; }
done

# One view per line: NAME|TERRAIN|OPTIONS (word-split).
views=()
for h in 0 45 90 135 180 225 270 315; do
  views+=("demo-h$h|demo|--heading $h --size 641x333")
done
views+=(
  "demo-pitch-30-1080p|demo|--pitch -30 --size 1920x1080"
  "demo-pitch+15-1080p|demo|--pitch 15 --size 1920x1080"
  "demo-bilinear|demo|--heading 45 --size 641x333 --surface bilinear"
  "demo-bilinear-pitch-30|demo|--heading 200 --pitch -30 --size 641x333 --surface bilinear"
  "demo-lod|demo|--heading 90 --size 641x333 --lod"
  "demo-lod-bilinear|demo|--heading 300 --pitch -12 --size 641x333 --lod --surface bilinear"
  "demo-near-step|demo|--heading 135 --pitch -20 --size 641x333 --near-step 0.5"
  "demo-near-step-bilinear|demo|--heading 20 --pitch -20 --size 641x333 --near-step 0.5 --surface bilinear"
  "demo-tilt-exact-pitch-30|demo|--heading 30 --pitch -30 --size 641x333 --projection tilt --tilt-method exact"
  "demo-tilt-exact-pitch+15|demo|--heading 250 --pitch 15 --size 641x333 --projection tilt --tilt-method exact"
  "demo-tilt-exact-bilinear|demo|--heading 160 --pitch -20 --size 641x333 --projection tilt --surface bilinear"
  "demo-tilt-exact-lod|demo|--heading 100 --pitch -10 --size 641x333 --projection tilt --lod"
  "demo-tilt-guedes-pitch-30|demo|--heading 30 --pitch -30 --size 641x333 --projection tilt --tilt-method guedes"
  "demo-tilt-guedes-pitch+15|demo|--heading 250 --pitch 15 --size 641x333 --projection tilt --tilt-method guedes"
  "demo-steep-tilt-exact|demo|--heading 60 --pitch -80 --size 641x333 --projection tilt --tilt-method exact"
  "demo-steep-tilt-guedes|demo|--heading 60 --pitch -80 --size 641x333 --projection tilt --tilt-method guedes"
  "demo-steep-tilt-up|demo|--heading 10 --pitch 75 --size 641x333 --projection tilt"
  "demo-at-agl|demo|--at 4000,5000 --agl 40 --heading 200 --pitch -10 --size 641x333"
  "demo-at-agl-tilt|demo|--at 4000,5000 --agl 40 --heading 200 --pitch -25 --size 641x333 --projection tilt"
  "demo-far-20480|demo|--heading 315 --far 20480 --size 1920x1080"
)
for bt in "$data"/bt/*.bt; do
  [ -f "$bt" ] || continue
  name=$(basename "$bt" .bt)
  for m in voxel raymarch voxel-literal; do
    views+=("$name-$m|$bt|--method $m --heading 135 --pitch -15 --size 641x333")
  done
  views+=("$name-voxel-tilt|$bt|--method voxel --heading 45 --pitch -35 --size 641x333 --projection tilt")
  views+=("$name-raymarch-tilt|$bt|--method raymarch --heading 45 --pitch -35 --size 641x333 --projection tilt")
done

render_all() { # BINARY DIR
  local bin=$1 dir=$2 line name terrain opts
  rm -rf "$dir" && mkdir -p "$dir" || return 1
  for line in "${views[@]}"; do
    IFS='|' read -r name terrain opts <<<"$line"
    # shellcheck disable=SC2086 # opts is a word list
    "$bin" render "$terrain" -o "$dir/$name.png" --depth "$dir/$name.tif" $opts >/dev/null 2>"$dir/$name.err" ||
      echo "failed" >"$dir/$name.failed"
  done
}

render_all "$old" "$out/before" || exit 2
render_all "$new" "$out/after" || exit 2

status=0
for line in "${views[@]}"; do
  IFS='|' read -r name _ <<<"$line"
  why=()
  for side in before after; do
    [ -e "$out/$side/$name.failed" ] && why+=("failed ($side: $(head -c 200 "$out/$side/$name.err"))")
  done
  if [ ${#why[@]} -eq 0 ]; then
    cmp -s "$out/before/$name.png" "$out/after/$name.png" || why+=(color)
    cmp -s "$out/before/$name.tif" "$out/after/$name.tif" || why+=(depth)
  fi
  if [ ${#why[@]} -eq 0 ]; then
    echo "identical $name"
  else
    echo "DIFFERENT $name (${why[*]})"
    status=1
  fi
done
exit $status
