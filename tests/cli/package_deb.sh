#!/usr/bin/env bash
# The .deb installs and runs without the source and build trees: CPack builds it from the
# build tree, dpkg -x unpacks it into a scratch prefix (no root needed), the unpacked tree is
# moved once more (relocatable), and its twinlight reports its shaders and content inside
# that tree and renders the default scene from there.
# Usage: package_deb.sh BUILD_DIR WORKDIR
set -euo pipefail
build=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
if ! cpack --config "$build/CPackConfig.cmake" -B "$work/package" >"$work/cpack.log" 2>&1; then
  cat "$work/cpack.log"
  exit 1
fi
deb=$(ls "$work"/package/twinlight_*.deb)
echo "package: $(basename "$deb"), $(du -k "$deb" | cut -f1) KiB"
dpkg-deb --field "$deb" Package Version Architecture Depends
contents=$(dpkg-deb --contents "$deb")
for f in ./usr/bin/twinlight ./usr/share/twinlight/shaders/common/composite.comp.spv \
         ./usr/share/twinlight/content/atrium.gltf ./usr/share/doc/twinlight/copyright; do
  grep -q " $f\$" <<<"$contents" || { echo "package_deb: $f missing from the package" >&2; exit 1; }
done

dpkg -x "$deb" "$work/unpacked"
mv "$work/unpacked" "$work/moved"
prefix="$work/moved/usr"
tl="$prefix/bin/twinlight"
"$tl" --version
info=$("$tl" info)
echo "$info"
grep -qx "shaders: $prefix/share/twinlight/shaders" <<<"$info" || { echo "package_deb: shaders not from the package" >&2; exit 1; }
grep -qx "content: $prefix/share/twinlight/content" <<<"$info" || { echo "package_deb: content not from the package" >&2; exit 1; }
cd "$work"
"$tl" render --size 48x27 --out "$work/atrium.png" --out "$work/atrium.exr"
test -s "$work/atrium.png" && test -s "$work/atrium.exr"
echo "package_deb: the unpacked package rendered the default scene"
