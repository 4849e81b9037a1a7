#!/usr/bin/env bash
# Redraws docs/images/meshlab-surface-diffusion.png: the "Surface diffusion N steps" dialog in
# Debian's MeshLab 2020.09 under Xvfb, over an ellipsoid (5/4/3, ~2500 vertices) evolved six steps
# by the filter (automatic τ, volume conserved) and coloured by its vertex quality H.
# The plugin is not installed system-wide: like the tests, MeshLab runs from a private prefix
# (meshlab_plugin/tests/prepare_prefix.sh; MeshLab loads plugins from <binary dir>/../lib/...),
# with a throwaway HOME so no saved settings change the picture. Needs a plugin build
# (-DSDFLOW_BUILD_MESHLAB_PLUGIN=ON, targets filter_sdflow sdflow) and
# `scripts/install-deps.sh --meshlab --screenshots`.
#   scripts/meshlab-screenshot.sh [BUILD_DIR] [OUTPUT]
#       (defaults build/release, docs/images/meshlab-surface-diffusion.png)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release} out=${2:-docs/images/meshlab-surface-diffusion.png}
tmp=$(mktemp -d) xvfb_pid='' gui_pid=''
cleanup() {
  [[ -z $gui_pid ]] || kill "$gui_pid" 2> /dev/null || true
  [[ -z $xvfb_pid ]] || kill "$xvfb_pid" 2> /dev/null || true
  rm -rf "$tmp"
}
trap cleanup EXIT

meshlab_lib=$(sed -n 's/^SDFLOW_MESHLAB_LIBRARY_DIR:PATH=//p' "$build/CMakeCache.txt")
plugin_dir=$(sed -n 's/^SDFLOW_MESHLAB_PLUGIN_DIR:STRING=//p' "$build/CMakeCache.txt")
meshlab_plugin/tests/prepare_prefix.sh "$build" "$tmp/prefix" "$plugin_dir" "$meshlab_lib" > /dev/null
cp "$(command -v meshlab)" "$tmp/prefix/bin/meshlab"  # a copy: a link would resolve to /usr/bin

# The mesh: sdflow's ellipsoid, then six steps of the filter and "Colorize by vertex Quality"
# (its range from a 1% percentile crop; minVal and maxVal are then unused) run by meshlabserver,
# saved with vertex colours and quality.
"$build/cli/sdflow" --quiet shape ellipsoid --vertices 2500 -o "$tmp/ellipsoid.ply" > /dev/null
# shellcheck source=SCRIPTDIR/../meshlab_plugin/tests/diffusion_filter_mlx.sh
source meshlab_plugin/tests/diffusion_filter_mlx.sh
{
  printf '<!DOCTYPE FilterScript>\n<FilterScript>\n'
  diffusion_filter_mlx 6 true 0.001 0.5 true false false 0.3 0 0 false
  cat << 'MLX'
 <filter name="Colorize by vertex Quality">
  <Param type="RichFloat" name="minVal" value="0"/>
  <Param type="RichFloat" name="maxVal" value="0"/>
  <Param type="RichDynamicFloat" name="perc" value="1" min="0" max="100"/>
  <Param type="RichBool" name="zeroSym" value="false"/>
 </filter>
</FilterScript>
MLX
} > "$tmp/evolve.mlx"
timeout 240 xvfb-run -a "$tmp/prefix/bin/meshlabserver" -i "$tmp/ellipsoid.ply" -o "$tmp/evolved.ply" -m vc vq \
  -s "$tmp/evolve.mlx" -l "$tmp/evolve.log" > "$tmp/console.txt" 2>&1 || { cat "$tmp/evolve.log"; exit 1; }
grep 'steps to t\|Quality Range' "$tmp/evolve.log" | sort -u

# The GUI on a free display with no window manager: place the windows with xdotool, open the
# dialog through MeshLab's filter search (Ctrl+F), move it right of the mesh, capture the screen.
display=99
while [[ -e /tmp/.X11-unix/X$display ]]; do display=$((display + 1)); done
export DISPLAY=:$display
Xvfb "$DISPLAY" -screen 0 1600x960x24 -nolisten tcp > "$tmp/xvfb.log" 2>&1 &
xvfb_pid=$!
sleep 2
HOME=$tmp XDG_CONFIG_HOME=$tmp/.config XDG_RUNTIME_DIR=$tmp "$tmp/prefix/bin/meshlab" "$tmp/evolved.ply" \
  > "$tmp/meshlab.log" 2>&1 &
gui_pid=$!
# place WINDOW X Y WIDTH HEIGHT: moves and resizes, again until it holds (early requests get lost).
place() {
  for _ in {1..20}; do
    xdotool windowmove "$1" "$2" "$3" windowsize "$1" "$4" "$5"
    sleep 0.5
    [[ $(xdotool getwindowgeometry --shell "$1" | grep -c "^WIDTH=$4\$\|^HEIGHT=$5\$") == 2 ]] && return
  done
  echo "meshlab-screenshot.sh: could not resize window $1" >&2
  exit 1
}
main=$(timeout 60 xdotool search --sync --onlyvisible --name 'MeshLab 2020' | head -n 1)
place "$main" 0 0 1600 960
sleep 2
xdotool windowfocus --sync "$main" key ctrl+f
sleep 1
xdotool type --delay 50 'Surface diffusion N steps'
sleep 1
xdotool key Down Return
dialog=$(timeout 30 xdotool search --sync --name '^Surface diffusion N steps$' | head -n 1)
place "$dialog" 935 60 657 770  # its full height: MeshLab shrinks it to fit the main window
xdotool mousemove 1599 959
sleep 2
import -window root "$tmp/screen.png"
convert "$tmp/screen.png" -strip "$out"
echo "meshlab-screenshot.sh: wrote $out"
