#!/usr/bin/env bash
# The bad-input table (not part of CI: the regression tests hold each case).
# Makes every bad input itself in a scratch folder, runs `overflight` on it and
# prints one Markdown row per case: the command, its exit status, the first
# line of standard error (or "-"), the stderr line count, and what it left
# behind where an output was asked for. Needs gdal-bin, python3 and, for the
# video, fly and full-disk cases, root, xvfb-run and ffmpeg.
#
#   scripts/bad_inputs.sh [OVERFLIGHT]     (default build/release/apps/overflight)
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bin="$(realpath "${1:-$root/build/release/apps/overflight}")"
work="$(mktemp -d)"
trap 'umount "$work/full" 2>/dev/null; rm -rf "$work"' EXIT
cd "$work"

# case NAME LEFTOVER-GLOB -- ARGS...: one row; LEFTOVER-GLOB lists what must not exist afterwards ("" = none checked).
case_row() {
  local name=$1 leftover=$2
  shift 3
  timeout 60 "$@" >out.txt 2>err.txt
  local status=$?
  local first lines left="-"
  first=$(head -n 1 err.txt | sed "s|$work/||g; s/|/\\\\|/g")
  lines=$(wc -l <err.txt)
  [ "$status" = 124 ] && first="(timed out after 60 s)"
  if [ -n "$leftover" ]; then
    # shellcheck disable=SC2086
    left=$(cd "$work" && ls -d $leftover 2>/dev/null | tr '\n' ' ')
    [ -n "$left" ] || left="nothing"
  fi
  printf '| %s | %s | %s | %s | %s |\n' "$name" "$status" "${first:--}" "$lines" "$left"
}

# --- inputs -----------------------------------------------------------------
gdal_create -q -of GTiff -outsize 100000 100000 -ot Int16 -co SPARSE_OK=TRUE -co TILED=YES huge.tif
gdal_create -q -of GTiff -outsize 5 4 -ot Int16 -burn 100 -a_srs EPSG:32610 -a_ullr 500000 5000120 500150 5000000 small.tif
gdal_translate -q -of USGSDEM small.tif profiles.dem
python3 - <<'PY'
d = bytearray(open('profiles.dem', 'rb').read())
d[858:864] = b'999999'  # Record A: number of profiles
open('profiles.dem', 'wb').write(d)
PY
gdal_create -q -of GTiff -outsize 3 3 -ot Float32 -burn 3e38 float38.tif
gdal_create -q -of GTiff -outsize 2 2 -ot Int16 -burn 7 two.tif
gdal_create -q -of GTiff -outsize 16 16 -bands 3 -ot Byte -burn 90 rgb.tif
mkdir -p set
printf 'P5\n3 3\n65535\n' >set/hf.pgm; head -c 18 /dev/zero >>set/hf.pgm
printf 'P6\n2 2\n255\n' >set/color.ppm; head -c 12 /dev/zero >>set/color.ppm
cp -r set big && printf 'h_scale = 1e300\nv_scale = 1\n' >big/map
cp -r set veh && printf 'h_scale = 10\nv_scale = 1\n[vehicle]\nx = 1000\nz = 5\n' >veh/map
printf '[[object]]\nkind = "box"\nx = 1\nz = 1\ncolor = [3E40, 0, 0]\n' >color.toml
"$bin" tile demo --demo-size 257 --tile-size 129 -o tiles >/dev/null 2>&1
edit_index() { # DIR PYTHON-STATEMENT-ON-j
  rm -rf "$1"; cp -r tiles "$1"
  python3 -c "import json; p='$1/index.json'; j=json.load(open(p)); $2; open(p,'w').write(json.dumps(j))"
}
edit_index claims16385 "j['tile_size'] = 16385"
edit_index hang "j['tile_size'] = 2**30 + 1"
edit_index lowmin "j['min_height'][0][0] = -1e30"
edit_index inf "j['max_height'][0][0] = 1e39"
rm -rf garbage && cp -r tiles garbage && tile=$(ls garbage/*.tif | grep -v overview | head -n 1) && head -c 5000 /dev/urandom >"$tile"
rm -rf brace && cp -r tiles brace && printf '{' >brace/index.json
(cd "$work" && xvfb-run -a "$bin" fly demo --demo-size 65 --frames 3 --size 64x36 --hidden --no-hud --record rec.csv >/dev/null 2>&1)
python3 - <<'PY'
lines = open('rec.csv').read().splitlines()
head = lines[0].split(',')
row = lines[3].split(',')
row[head.index('pitch')] = '90'
lines[3] = ','.join(row)
open('pitch90.csv', 'w').write('\n'.join(lines) + '\n')
PY
cp small.tif locked.tif && chmod 000 locked.tif && chmod 755 "$work"
mkdir -p full && mount -t tmpfs -o size=64k tmpfs full && head -c 60000 /dev/zero >full/filler 2>/dev/null

# --- the table ---------------------------------------------------------------
echo "| case | exit | first line of stderr | stderr lines | left behind |"
echo "|---|---:|---|---:|---|"
case_row "sparse GeoTIFF 100000², info under 512 MiB" "" -- prlimit --as=536870912 "$bin" info huge.tif
case_row "USGS DEM claiming 999999 profiles, info under 512 MiB" "" -- prlimit --as=536870912 "$bin" info profiles.dem
case_row "Float32 DEM of 3e38, info" "" -- "$bin" info float38.tif
case_row "Float32 DEM of 3e38, render" "o1.png" -- "$bin" render float38.tif -o o1.png
case_row "map h_scale = 1e300" "" -- "$bin" info big
case_row "map [vehicle] start off the terrain, sim" "" -- "$bin" sim veh --steps 3
case_row "scene color 3E40" "o2.png" -- "$bin" render demo --demo-size 33 --scene color.toml -o o2.png
case_row "RGB image as a DEM, info (a warning, exit 0)" "" -- "$bin" info rgb.tif
case_row "RGB image as a DEM, render (a warning, exit 0)" "" -- "$bin" render rgb.tif -o o12.png
case_row "2x2 raster, tile" "" -- "$bin" tile two.tif -o two_tiles --tile-size 3
case_row "eye under the surface" "o3.png" -- "$bin" render demo --demo-size 65 --eye 320,1,320 -o o3.png
case_row "index.json claims 16385² tiles of 129² files, info under 512 MiB" "" -- prlimit --as=536870912 "$bin" info claims16385
case_row "index.json claims 16385² tiles, render quadtree under 512 MiB" "o4.png" -- prlimit --as=536870912 "$bin" render claims16385 --method quadtree -o o4.png
case_row "index.json tile size 2^30+1, info (was a hang)" "" -- "$bin" info hang
case_row "index.json min_height -1e30" "o5.png" -- "$bin" render lowmin --method quadtree -o o5.png
case_row "index.json max_height 1e39" "o6.png" -- "$bin" render inf --method quadtree -o o6.png
case_row "a tile replaced by garbage, render quadtree" "o7.png" -- "$bin" render garbage --method quadtree -o o7.png
case_row "a tile replaced by garbage, tile again (resume)" "" -- "$bin" tile demo --demo-size 257 --tile-size 129 -o garbage
case_row "index.json = {" "" -- "$bin" info brace
case_row "render -o ''" "" -- "$bin" render demo --demo-size 33 -o ''
case_row "render -o onto a full disk" "full/.o* full/o8.png" -- "$bin" render demo --demo-size 129 -o full/o8.png
case_row "render --depth onto a full disk" "full/.d* full/d.tif o9.png" -- "$bin" render demo --demo-size 129 -o o9.png --depth full/d.tif
case_row "tile onto a full disk" "full/t/.*tmp*" -- "$bin" tile demo --demo-size 257 --tile-size 129 -o full/t
case_row "sim > /dev/full" "" -- bash -c "'$bin' sim demo --demo-size 65 --steps 5 >/dev/full"
case_row "sim --steps 99999999999999999999" "" -- "$bin" sim demo --demo-size 65 --steps 99999999999999999999
case_row "sim --steps 010 (decimal 10, exit 0)" "" -- bash -c "'$bin' sim demo --demo-size 65 --steps 010 | tail -n 1 | cut -d, -f1"
case_row "replay CSV with pitch 90" "frames90" -- "$bin" fly demo --demo-size 65 --replay pitch90.csv --out frames90
case_row "replay --video x'\$(touch pwned)'.mp4 (exit 0)" "pwned" -- "$bin" fly demo --demo-size 65 --replay rec.csv --size 64x36 --out frames_v --video "x'\$(touch pwned)'.mp4"
case_row "replay --video into a missing folder" "frames_m" -- "$bin" fly demo --demo-size 65 --replay rec.csv --size 64x36 --out frames_m --video nowhere/v.mp4
case_row "unreadable terrain file (as nobody)" "" -- setpriv --reuid=nobody --regid=nogroup --clear-groups "$bin" info "$work/locked.tif"
case_row "render --triangles 1" "" -- "$bin" render demo --demo-size 33 --method roam --triangles 1 -o o10.png
case_row "render --cache-mib 0" "" -- "$bin" render demo --demo-size 33 --method quadtree --cache-mib 0 -o o11.png
case_row "tile --tile-size 6" "" -- "$bin" tile demo --demo-size 33 --tile-size 6 -o t6
case_row "missing terrain file" "" -- "$bin" info nowhere.tif
printf '{"eye": [1, 2]}' >badcam.json
case_row "render --camera with a 2-number eye" "cam1.png" -- "$bin" render demo --demo-size 33 --camera badcam.json -o cam1.png
case_row "render --camera not JSON" "cam2.png" -- "$bin" render demo --demo-size 33 --camera rec.csv -o cam2.png
case_row "render --look-at lonlat: on the demo (no CRS)" "cam3.png" -- "$bin" render demo --demo-size 33 --look-at lonlat:1,2 -o cam3.png
case_row "render --crs EPSG:4326 on the demo (no CRS)" "cam4.png" -- "$bin" render demo --demo-size 33 --crs EPSG:4326 --at 1,2 -o cam4.png
case_row "info --at outside the terrain" "" -- "$bin" info demo --demo-size 33 --at 5000,5000
echo
echo "3-frame replay of the voxel method, ms per step (was composite:1225059.59):"
"$bin" fly demo --demo-size 65 --method voxel --replay rec.csv --frames 3 --size 64x36 --out frames_t | tail -n 1
