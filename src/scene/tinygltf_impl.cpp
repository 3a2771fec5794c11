// tinygltf (Debian libtinygltf-dev, the header libtinygltf.so is built from) compiled into
// tessera instead of linked as a shared library: one fewer to map and relocate at every start
// of the CLI. Its image callbacks are tessera's (gltf_loader.cpp), so its stb_image reader and
// writer are left out (TINYGLTF_NO_STB_IMAGE[_WRITE], defined for the whole library in
// src/CMakeLists.txt so every file sees the same TinyGLTF class). Built without the
// sanitizers, as the shared library was.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
