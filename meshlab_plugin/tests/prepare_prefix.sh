#!/usr/bin/env bash
# Makes PREFIX a private MeshLab installation holding the freshly built plugin, so the tests never
# touch the system's MeshLab: meshlabserver only loads plugins from
# <directory of its binary>/../lib/<arch>/meshlab/plugins, so PREFIX gets a copy of the binary (a
# symbolic link would resolve to /usr/bin), links to libmeshlab-common.so and to Debian's plugins,
# and the plugin installed by `cmake --install`.
#   prepare_prefix.sh BUILD_DIR PREFIX PLUGIN_DIR MESHLAB_LIBRARY_DIR
# PLUGIN_DIR is relative to the prefix (lib/x86_64-linux-gnu/meshlab/plugins); MESHLAB_LIBRARY_DIR
# is Debian's (/usr/lib/x86_64-linux-gnu/meshlab).
set -euo pipefail
build=$1 prefix=$2 plugin_dir=$3 system_dir=$4

rm -rf "$prefix"
mkdir -p "$prefix/bin" "$prefix/$plugin_dir"
cp "$(command -v meshlabserver)" "$prefix/bin/meshlabserver"
ln -s "$system_dir/libmeshlab-common.so" "$prefix/$plugin_dir/../libmeshlab-common.so"
for plugin in "$system_dir"/plugins/*.so; do
  # An sdflow plugin already installed system-wide must not shadow the one under test.
  [[ $(basename "$plugin") == libfilter_sdflow.so ]] || ln -s "$plugin" "$prefix/$plugin_dir/"
done
cmake --install "$build" --prefix "$prefix" --component meshlab_plugin > /dev/null
test -f "$prefix/$plugin_dir/libfilter_sdflow.so"
echo "prepare_prefix: meshlabserver with the sdflow plugin in $prefix"
