#!/usr/bin/env bash
# A worker links no scene parser and no image library (issue 22: the coordinator sends it a
# prepared scene): photonfarm-worker's shared libraries, resolved by ldd, include no
# OpenImageIO, Draco, OpenCV, GDAL, libpng/jpeg/tiff or TinyGLTF. Prints how many it needs.
# Usage: worker_links_test.sh PHOTONFARM_WORKER
set -euo pipefail
worker=$1
libraries=$(ldd "$worker")
forbidden=$(grep -Ei 'libOpenImageIO|libdraco|libopencv|libgdal|libpng|libjpeg|libtiff|tinygltf' \
    <<<"$libraries" || true)
echo "worker_links: $(wc -l <<<"$libraries") shared libraries"
if [ -n "$forbidden" ]; then
    echo "worker_links: photonfarm-worker links what only the coordinator may:" >&2
    echo "$forbidden" >&2
    exit 1
fi
