# Sourced by the benches that run the Vulkan backend.
# vulkan_device BUILD_DIR: prints the device `--backend vulkan` picks here, as
# photonfarm-worker --list-devices names it (nothing where there is none).
vulkan_device() {
    "$1/worker/photonfarm-worker" --list-devices 2>/dev/null |
        sed -n 's/^vulkan device [0-9]*: \(.*[^ ]\) *<- --backend vulkan uses this one.*/\1/p' | head -1
}
