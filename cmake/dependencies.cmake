# Every dependency comes from a Debian 12 package (scripts/setup.sh installs them).
find_package(PkgConfig REQUIRED)
pkg_check_modules(SPNG REQUIRED IMPORTED_TARGET spng)   # PNG read/write (libspng-dev)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)     # JPEG/TGA/BMP read (libstb-dev)
find_package(ZLIB REQUIRED)                             # zlib streams (Ptex, PNG)
find_package(TBB REQUIRED)                              # parallel_for (libtbb-dev)
find_package(CLI11 CONFIG REQUIRED)                     # command line (libcli11-dev)
find_package(nlohmann_json 3 CONFIG REQUIRED)           # --json output (nlohmann-json3-dev)
