# Probes for optional tools, sourced by the scripts of this folder (bash,
# under `set -euo pipefail`). Every probe here is a condition or ends in
# `|| ...`, never a bare pipeline or command substitution: under `set -e` a
# missing tool (exit status 127) or a pipeline cut short (SIGPIPE, 141) would
# otherwise end the calling script with no message.
# tests/scripts.rs runs the scripts' `--probe` modes with a PATH that lacks
# each optional tool in turn.

# True when TOOL can be run.
have() {
    command -v "$1" >/dev/null 2>&1
}

# Ends the calling script when TOOL is missing, saying what provides it.
require() {
    local tool=$1 provider=$2
    have "$tool" && return 0
    echo "$(basename "$0"): $tool is missing: $provider" >&2
    exit 2
}

# The Debian packages the tests need that are not installed, one a line:
# lavapipe (Mesa's Vulkan driver on the CPU) and the Vulkan loader, Xvfb,
# xdotool and ImageMagick for the window tests, Chromium for the page's.
# RAYSANDBOX_VULKAN_ICD_DIR names where Vulkan drivers register (Debian's
# folder by default; the probe's test points it at an empty folder).
missing_test_packages() {
    have_lavapipe || echo mesa-vulkan-drivers
    have_vulkan_loader || echo libvulkan1
    have Xvfb || echo xvfb
    have xdotool || echo xdotool
    have import || echo imagemagick
    have chromium || echo chromium
}

# True when lavapipe's Vulkan driver is registered.
have_lavapipe() {
    local icd
    for icd in "${RAYSANDBOX_VULKAN_ICD_DIR:-/usr/share/vulkan/icd.d}"/lvp_icd.*.json; do
        [ -e "$icd" ] && return 0
    done
    return 1
}

# True when the dynamic linker knows libvulkan.so.1. ldconfig lives in
# /sbin, which a user's PATH may lack; its list is read whole (no `grep -q`
# on a pipe, whose early exit would fail the pipeline under pipefail).
have_vulkan_loader() {
    local ldconfig libraries
    ldconfig=$(command -v ldconfig || echo /sbin/ldconfig)
    [ -x "$ldconfig" ] || return 1
    libraries=$("$ldconfig" -p 2>/dev/null) || return 1
    [[ $libraries == *"libvulkan.so.1 "* ]]
}

# Installs Debian packages, as root or through sudo; a clear error where
# neither apt-get nor a way to become root exists.
install_packages() {
    local sudo=""
    if ! have apt-get; then
        echo "$(basename "$0"): apt-get is missing: install these Debian packages (or your system's equivalents) by hand: $*" >&2
        exit 2
    fi
    if [ "$(id -u)" -ne 0 ]; then
        require sudo "run as root, or install these Debian packages by hand: $*"
        sudo=sudo
    fi
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "$@"
}

# True when the toolchain has the standard library for wasm32: asks rustup
# when there is one, else looks in rustc's sysroot (a toolchain installed
# without rustup).
have_wasm32_target() {
    local installed sysroot
    if have rustup; then
        installed=$(rustup target list --installed 2>/dev/null) || return 1
        [[ $'\n'$installed$'\n' == *$'\nwasm32-unknown-unknown\n'* ]]
    else
        sysroot=$(rustc --print sysroot 2>/dev/null) || return 1
        [ -d "$sysroot/lib/rustlib/wasm32-unknown-unknown" ]
    fi
}

# The version of wasm-bindgen on PATH ("" when there is none).
wasm_bindgen_version() {
    have wasm-bindgen || return 0
    wasm-bindgen --version 2>/dev/null | sed -n 's/^wasm-bindgen \([^ ]*\).*/\1/p' || true
}

# The major version of binaryen's wasm-opt on PATH ("" when there is none).
wasm_opt_version() {
    have wasm-opt || return 0
    wasm-opt --version 2>/dev/null | sed -n 's/^wasm-opt version \([0-9]*\).*/\1/p' || true
}
