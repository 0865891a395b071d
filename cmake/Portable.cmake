# The portable build (SHADERLAB_PORTABLE; scripts/portable-build.sh runs it in a Debian 11 chroot):
# one grader-only `shaderlab` that starts on any x86-64 Linux with glibc 2.31 or later, whatever
# else is installed. It defines the targets that the top-level CMakeLists.txt otherwise finds, so
# no library's CMakeLists knows the difference:
#   - glibc (libc, libm, libdl, libpthread, librt) stays dynamic: it is the base system, and a
#     binary linked on the oldest glibc it supports runs on every newer one;
#   - libstdc++ and libgcc are linked in (-static-libstdc++ -static-libgcc): Debian 11's GCC 10
#     wants a libstdc++ newer than some systems have, and Mesa loads its own beside ours;
#   - every other library is linked from its static archive (.a), with the archives it needs in
#     turn (pkg-config --static); a missing archive stops the configure, naming the package;
#   - Mesa (libOSMesa, libEGL, libGL) is not linked at all: framework/gl opens it at run time.
# Gaps, each said where it applies: Debian 11 ships libmeshoptimizer only as a shared library, so
# this build reads no EXT_meshopt_compression scene (the loader says so; no bundled scene uses it);
# cpp-httplib and tinygltf are compiled here from their single headers (see below).
set(CMAKE_FIND_LIBRARY_SUFFIXES .a)
add_link_options(-static-libstdc++ -static-libgcc)
# `gradescope-bundle` packs a portable program itself and recognises one given with --binary.
add_compile_definitions(SHADERLAB_PORTABLE_BUILD=1)

# glibc's libraries, linked dynamically whatever pkg-config --static lists.
set(SHADERLAB_GLIBC_LIBS c m dl pthread rt)

# shaderlab_static_archive(<var> <name> <package>): the full path of lib<name>.a in <var>, or a
# configure error naming the Debian package that ships it.
function(shaderlab_static_archive var name package)
  find_library(SHADERLAB_STATIC_${name} NAMES lib${name}.a)
  if(NOT SHADERLAB_STATIC_${name})
    message(FATAL_ERROR "portable build: no static archive lib${name}.a; install ${package}")
  endif()
  set(${var} ${SHADERLAB_STATIC_${name}} PARENT_SCOPE)
endfunction()

# shaderlab_static_pkg(<PREFIX> <module> <package> [ALSO <module>...]): PkgConfig::<PREFIX> as
# pkg_check_modules would make it, but linking the module's archive and those of its private
# dependencies (pkg-config --static), then those of the ALSO modules: dependencies that the
# module's .pc names in Libs.private without their own. An archive listed twice is kept where it
# comes last, after everything that needs it.
function(shaderlab_static_pkg prefix module package)
  cmake_parse_arguments(ARG "" "" "ALSO" ${ARGN})
  pkg_check_modules(${prefix} REQUIRED ${module})
  set(names ${${prefix}_STATIC_LIBRARIES})
  foreach(also IN LISTS ARG_ALSO)
    string(MAKE_C_IDENTIFIER "${also}" also_prefix)
    pkg_check_modules(SHADERLAB_${also_prefix} REQUIRED ${also})
    list(APPEND names ${SHADERLAB_${also_prefix}_STATIC_LIBRARIES})
  endforeach()
  list(REVERSE names)
  list(REMOVE_DUPLICATES names)
  list(REVERSE names)
  set(libs)
  foreach(name IN LISTS names)
    if(name IN_LIST SHADERLAB_GLIBC_LIBS)
      list(APPEND libs ${name})
    else()
      shaderlab_static_archive(archive ${name} "${package} (and the -dev packages of ${module}'s dependencies)")
      list(APPEND libs ${archive})
    endif()
  endforeach()
  add_library(PkgConfig::${prefix} INTERFACE IMPORTED)
  set_target_properties(PkgConfig::${prefix} PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${${prefix}_INCLUDE_DIRS}"
    INTERFACE_COMPILE_OPTIONS "${${prefix}_CFLAGS_OTHER}"
    INTERFACE_LINK_LIBRARIES "${libs}")
endfunction()

shaderlab_static_pkg(STB stb libstb-dev)
# libarchive's zip writer brings its table of every writer, the xar one among them, and with it
# libxml2, which needs ICU (28 MB of its data are the larger part of the program).
shaderlab_static_pkg(LIBARCHIVE libarchive libarchive-dev ALSO libxml-2.0)
shaderlab_static_pkg(XXHASH libxxhash libxxhash-dev)

find_package(PNG REQUIRED)  # FindPNG and FindZLIB find libpng16.a and libz.a (the suffix above)

shaderlab_static_archive(draco_archive draco libdraco-dev)
add_library(draco::draco INTERFACE IMPORTED)
set_target_properties(draco::draco PROPERTIES INTERFACE_LINK_LIBRARIES ${draco_archive})

# No libmeshoptimizer.a in Debian 11: a stand-in that tells the loader (SHADERLAB_NO_MESHOPT).
add_library(meshoptimizer::meshoptimizer INTERFACE IMPORTED)
set_target_properties(meshoptimizer::meshoptimizer PROPERTIES INTERFACE_COMPILE_DEFINITIONS SHADERLAB_NO_MESHOPT=1)

# tinygltf is one header; Debian builds its implementation into a shared library only, so the
# implementation is compiled here from the same header (stb_image's comes from libstb.a).
find_path(SHADERLAB_TINYGLTF_INCLUDE tiny_gltf.h)
if(NOT SHADERLAB_TINYGLTF_INCLUDE)
  message(FATAL_ERROR "portable build: tiny_gltf.h not found; install libtinygltf-dev")
endif()
add_library(shaderlab_tinygltf STATIC ${CMAKE_CURRENT_LIST_DIR}/portable/tinygltf_implementation.cpp)
target_include_directories(shaderlab_tinygltf SYSTEM PUBLIC ${SHADERLAB_TINYGLTF_INCLUDE})
target_link_libraries(shaderlab_tinygltf PRIVATE nlohmann_json::nlohmann_json PkgConfig::STB)
add_library(TinyGLTF::TinyGLTF ALIAS shaderlab_tinygltf)

# cpp-httplib: Debian ships it (12 and later) as a compiled library whose header holds only
# declarations, and Debian 11 not at all. portable-build.sh takes upstream's single header, which
# holds the implementation, from Debian 12's source package; it is used header-only, plain HTTP
# (the workbench listens on the loopback: no TLS, no compression).
find_path(SHADERLAB_HTTPLIB_INCLUDE httplib.h PATH_SUFFIXES cpp-httplib-header-only)
if(NOT SHADERLAB_HTTPLIB_INCLUDE)
  message(FATAL_ERROR "portable build: cpp-httplib's single header (httplib.h) not found; "
                      "scripts/portable-build.sh fetches it, or pass -DSHADERLAB_HTTPLIB_INCLUDE=DIR")
endif()
file(STRINGS ${SHADERLAB_HTTPLIB_INCLUDE}/httplib.h httplib_impl REGEX "^inline .*detail::|^inline bool Server::listen")
if(NOT httplib_impl)
  message(FATAL_ERROR "portable build: ${SHADERLAB_HTTPLIB_INCLUDE}/httplib.h holds declarations only "
                      "(Debian's split header); the portable build needs upstream's single header")
endif()
find_package(Threads REQUIRED)
add_library(PkgConfig::HTTPLIB INTERFACE IMPORTED)
set_target_properties(PkgConfig::HTTPLIB PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES ${SHADERLAB_HTTPLIB_INCLUDE}
  INTERFACE_LINK_LIBRARIES Threads::Threads)
# What framework/serve's configure check reads.
set(HTTPLIB_INCLUDE_DIRS ${SHADERLAB_HTTPLIB_INCLUDE})
set(HTTPLIB_CFLAGS_OTHER "")
