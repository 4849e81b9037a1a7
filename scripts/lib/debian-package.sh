# Sourced by scripts that read the files of a Debian package without installing it
# (repair-samples.sh, robustness.sh); they set $work to a temporary directory first.

# The directory PATH of Debian package PACKAGE: installed, or extracted from its downloaded .deb.
package_path() {
  local package=$1 path=$2
  if [[ ! -e "$path" ]]; then
    (cd "$work" && apt-get download "$package" > /dev/null 2>&1 && dpkg-deb -x "$package"_*.deb "$package")
    path="$work/$package$path"
  fi
  echo "$path"
}
