# Every find_package of the project, in one place. All come from Debian 12 packages
# (deploy/install-deps.sh); see ../shared/STACK.md for the pitfalls handled here.
find_package(Threads REQUIRED)
find_package(absl CONFIG REQUIRED)
find_package(Protobuf REQUIRED)  # module mode: Debian ships no protobuf-config.cmake
find_package(embree 3 REQUIRED)
find_package(TBB CONFIG REQUIRED)
find_package(OpenEXR CONFIG REQUIRED)
find_package(spdlog CONFIG REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
find_package(ZLIB REQUIRED)  # pbrt's .pbrt.gz and .ply.gz
find_package(draco CONFIG REQUIRED)  # glTF KHR_draco_mesh_compression
find_package(meshoptimizer CONFIG REQUIRED)  # glTF EXT_meshopt_compression
find_package(CLI11 CONFIG REQUIRED)
find_package(OpenSSL REQUIRED)  # SHA-256 content addresses
find_package(zstd CONFIG REQUIRED)  # blobs and images on the wire
find_package(gRPC CONFIG REQUIRED)
find_package(prometheus-cpp CONFIG REQUIRED)  # the coordinator's /metrics
find_package(nlohmann_json CONFIG REQUIRED)  # the dashboard's small JSON; tests edit glTF JSON
# Debian ships pkg-config files only for these two.
find_package(PkgConfig REQUIRED)
pkg_check_modules(stb REQUIRED IMPORTED_TARGET stb)  # PNG encoding (stb_image_write)
pkg_check_modules(httplib REQUIRED IMPORTED_TARGET cpp-httplib)  # the dashboard's HTTP(S)
# Headers and glslc only: the worker opens libvulkan.so.1 at run time (vk_api.cpp), so it
# starts, and says why, on machines without a Vulkan loader.
find_package(Vulkan REQUIRED COMPONENTS glslc)

# OpenImageIO's imported target names /usr/include/opencv4, which Debian does not ship
# without OpenCV: drop that path so generation succeeds.
find_package(OpenImageIO CONFIG REQUIRED)
get_target_property(_pf_oiio_includes OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
list(FILTER _pf_oiio_includes EXCLUDE REGEX "opencv")
set_target_properties(OpenImageIO::OpenImageIO PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${_pf_oiio_includes}")

if(PF_BUILD_TESTS)
    find_package(GTest CONFIG REQUIRED)
    include(GoogleTest)
endif()
if(PF_BUILD_BENCH)
    find_package(benchmark CONFIG REQUIRED)
endif()
