// tinyobjloader (Debian libtinyobjloader-dev, the header libtinyobjloader.so is built from)
// compiled into tessera instead of linked as a shared library: one fewer to map and relocate
// at every start of the CLI. Built without the sanitizers, as the shared library was.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
