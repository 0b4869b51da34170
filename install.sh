#!/usr/bin/env bash
# Set up sdfgl on a fresh Debian/Ubuntu machine: Mesa EGL (and, with --test, Xvfb,
# xdotool, glslang-tools and chromium for the browser tests, prusa-slicer for the print-file tests), a virtual environment in .venv, and the package in it.
#   ./install.sh          the library, the `sdfgl` command and every optional feature ([all])
#   ./install.sh --test   also what the test suite needs
set -euo pipefail
cd "$(dirname "$0")"

with_tests=0
[ "${1:-}" = "--test" ] && with_tests=1

packages=(libegl1 libegl-mesa0 libgl1-mesa-dri)
[ "$with_tests" = 1 ] && packages+=(xvfb xdotool glslang-tools chromium prusa-slicer)

missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
    echo "install.sh: installing system packages: ${missing[*]}"
    if [ "$(id -u)" = 0 ]; then
        apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
    elif command -v sudo >/dev/null && sudo -n true 2>/dev/null; then
        sudo apt-get update -qq && sudo DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
    else
        echo "install.sh: missing system packages and no root rights. Run:" >&2
        echo "    sudo apt-get install -y ${missing[*]}" >&2
        exit 1
    fi
fi

python3 -m venv .venv
if [ "$with_tests" = 1 ]; then
    .venv/bin/pip install -q --disable-pip-version-check -e ".[test]"
    # an editable install leaves the sources uncompiled, and where PYTHONDONTWRITEBYTECODE is
    # set every process would compile them again (a third of `sdfgl render`'s start-up)
    .venv/bin/python -m compileall -q sdfgl
else
    .venv/bin/pip install -q --disable-pip-version-check ".[all]"
fi
echo "install.sh: sdfgl installed in $(pwd)/.venv"
