#!/usr/bin/env bash
# The two large DEMs of the large-raster benchmarks (`info`, `tile`, a first
# quadtree frame): a SIZE x SIZE Int16 DEFLATE GeoTIFF in a projected CRS and
# one in geographic coordinates, both upsampled (cubic) from the SRTM tile of
# Mt Fuji in ../shared/data (3" cells, no voids), so that they compress and
# look like a real regional DEM rather than noise.
#
#   bench/make_large_dem.sh [OUT_DIR [SIZE]]
#
# OUT_DIR defaults to /tmp/overflight-large-dem (never the repository), SIZE to
# 20000. It writes:
#   utm.tif  EPSG:32654 (UTM 54N), a square around 138.5E 35.5N that lies
#            inside the tile (no no-data), 80 km across;
#   geo.tif  EPSG:4326, the whole 1-degree tile (the tiler reprojects it to
#            UTM, so the warped grid has no-data wedges along its edges).
# Environment: DATA (the shared data folder, default ../shared/data beside the
# repository). A file already of the right size is kept.
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
data=${DATA:-$here/../shared/data}
out=${1:-/tmp/overflight-large-dem}
size=${2:-20000}
src=$data/srtm/mt_fuji_90m.tif
[ -f "$src" ] || { echo "make_large_dem.sh: $src: missing (set DATA)" >&2; exit 1; }
mkdir -p "$out"

co=(-of GTiff -co TILED=YES -co BLOCKXSIZE=256 -co BLOCKYSIZE=256 -co COMPRESS=DEFLATE -co PREDICTOR=2 -co BIGTIFF=IF_SAFER)

made() { # made FILE: FILE exists with SIZE x SIZE samples
    [ -f "$1" ] && gdalinfo "$1" 2>/dev/null | grep -q "^Size is $size, $size\$"
}

# 273244 3931367 is 138.5E 35.5N in UTM 54N; 40 km either way stays inside the tile.
if ! made "$out/utm.tif"; then
    gdalwarp -q -overwrite -t_srs EPSG:32654 -te 233244 3891367 313244 3971367 -ts "$size" "$size" -r cubic \
        -ot Int16 -wm 512 "${co[@]}" "$src" "$out/utm.tif.part"
    mv "$out/utm.tif.part" "$out/utm.tif"
fi
if ! made "$out/geo.tif"; then
    gdalwarp -q -overwrite -ts "$size" "$size" -r cubic -ot Int16 -wm 512 "${co[@]}" "$src" "$out/geo.tif.part"
    mv "$out/geo.tif.part" "$out/geo.tif"
fi
ls -l "$out/utm.tif" "$out/geo.tif"
