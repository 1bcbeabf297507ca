# Every third-party library is a Debian 12 package (scripts/deps.sh installs them).
find_package(Threads REQUIRED)
find_package(Vulkan REQUIRED COMPONENTS glslangValidator)
find_package(glm CONFIG REQUIRED)
find_package(glfw3 CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_package(TBB CONFIG REQUIRED)
find_package(embree 3 CONFIG REQUIRED)
find_package(GTest CONFIG REQUIRED)
find_package(PkgConfig REQUIRED)

# Draco: Debian ships a CMake package config.
find_package(draco CONFIG REQUIRED)

# meshoptimizer (libmeshoptimizer-dev ships a CMake package config): `bounce vlm-make` simplifies with it.
find_package(meshoptimizer CONFIG REQUIRED)

# tinygltf (header-only, Debian builds it against system nlohmann-json and stb).
find_path(TINYGLTF_INCLUDE_DIR tiny_gltf.h REQUIRED)

# stb: headers under /usr/include/stb, implementation in libstb.
find_path(STB_INCLUDE_DIR stb_image.h PATH_SUFFIXES stb REQUIRED)
find_library(STB_LIBRARY stb REQUIRED)

# OpenSubdiv: no CMake config in Debian's libosd-dev.
find_path(OSD_INCLUDE_DIR opensubdiv/version.h REQUIRED)
find_library(OSD_CPU_LIBRARY osdCPU REQUIRED)
add_library(bounce_opensubdiv INTERFACE)
target_include_directories(bounce_opensubdiv INTERFACE ${OSD_INCLUDE_DIR})
target_link_libraries(bounce_opensubdiv INTERFACE ${OSD_CPU_LIBRARY})

add_library(bounce_stb INTERFACE)
target_include_directories(bounce_stb INTERFACE ${STB_INCLUDE_DIR})
target_link_libraries(bounce_stb INTERFACE ${STB_LIBRARY})

add_library(bounce_tinygltf INTERFACE)
target_include_directories(bounce_tinygltf INTERFACE ${TINYGLTF_INCLUDE_DIR})
target_link_libraries(bounce_tinygltf INTERFACE nlohmann_json::nlohmann_json bounce_stb)
