# `cpack -G DEB` in a build folder: a Debian package of what `cmake --install` installs, under
# /usr: the command line, libraylane.so and .a, the headers, the CMake and pkg-config files, the
# Python module (in /usr/lib/python3/dist-packages), the man page and bash completion. Its
# dependencies on shared libraries (oneTBB, OpenEXR, zlib, the C++ runtime) are computed from the
# binaries by dpkg-shlibdeps (Debian's dpkg-dev). packaging/deb_test.sh unpacks it and runs it.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME raylane)
set(CPACK_PACKAGE_VENDOR "Raylane")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "SIMD packet ray tracer: command line, C++ library and Python module")
set(CPACK_PACKAGE_DESCRIPTION
  "Raylane renders scenes and models with a SIMD packet path (SSE4.2, AVX2 or AVX-512, chosen at start-up) checked against a scalar path, and answers batches of ray queries against triangle meshes, from the command line, from C++ (libraylane) and from Python.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "Raylane developers")
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# the Python module imports NumPy when it makes arrays; the command line needs neither
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3, python3-numpy")
set(CPACK_STRIP_FILES ON)
include(CPack)
