#!/usr/bin/env bash
# Fetches the headers of Debian's MeshLab 2020.09 (and its vcglib) from Debian's source package,
# with Debian's patches applied, into a directory (default: third_party/meshlab-src). Uses a
# private deb-src list, so the system's apt configuration is left untouched.
set -euo pipefail
dest=$(realpath -m "${1:-$(dirname "$0")/../third_party/meshlab-src}")
if [[ -f "$dest/src/common/interfaces.h" || -f "$dest/src/common/interfaces/filter_plugin_interface.h" ]]; then
  echo "fetch-meshlab-source: already in $dest"; exit 0
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/lists/partial" "$work/src"
cat > "$work/sources.list" <<LIST
deb-src [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://deb.debian.org/debian bookworm main
LIST
apt_opts=(-o "Dir::Etc::SourceList=$work/sources.list" -o "Dir::Etc::SourceParts=/dev/null"
          -o "Dir::State::Lists=$work/lists" -o "Debug::NoLocking=1")
apt-get "${apt_opts[@]}" update -qq
(cd "$work/src" && apt-get "${apt_opts[@]}" source -qq meshlab=2020.09+dfsg1-2 2>/dev/null \
   || apt-get "${apt_opts[@]}" source -qq meshlab)
unpacked=$(find "$work/src" -maxdepth 1 -mindepth 1 -type d | head -n 1)
mkdir -p "$(dirname "$dest")"
rm -rf "$dest"
mv "$unpacked" "$dest"
echo "fetch-meshlab-source: MeshLab sources in $dest"
