# `cmake --install`: the localizer as a package other projects find (find_package(bimloc) or
# pkg-config), and the `bimloc` command when the bench is built. Included at the end of the
# top-level CMakeLists.txt, after every target exists.
#
# Layout (GNUInstallDirs; CMake's own convention, as PRBonn/kiss-icp and koide3/small_gicp use):
#   include/bimloc/**                    the public headers (Eigen and nlohmann_json only)
#   lib/libbimloc_localizer.so.0.1.0     bimloc::localizer, shared (see below)
#   lib/cmake/bimloc/bimloc*.cmake       the package config, its version file, the targets
#   lib/pkgconfig/bimloc.pc              the same for pkg-config
#   bin/bimloc                           the command (BIMLOC_BUILD_SIM=ON only)
#
# Why a shared library: the localizer links PCL, Ceres and IFC++ privately, and its public
# headers include none of them. Shared, they stay its own business: a consumer needs only Eigen
# and nlohmann_json (what the headers include), and IFC++, which Debian puts off the linker path
# in /usr/lib/ifcplusplus, is found through the library's RUNPATH. Static, every consumer would
# have to find PCL (with VTK behind it), Ceres and IFC++ itself just to link.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(BIMLOC_CMAKE_INSTALL_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/bimloc")

# The consumer-facing name is bimloc::localizer, the same in the build tree (the ALIAS) and
# installed (the exported target, namespaced). SOVERSION follows SameMajorVersion below.
set_target_properties(bimloc_localizer PROPERTIES
  EXPORT_NAME localizer
  VERSION ${PROJECT_VERSION}
  SOVERSION ${PROJECT_VERSION_MAJOR})
# Shared code is compiled -fPIC, where GCC assumes any exported function may be replaced at
# load time (ELF interposition) and so stops inlining calls to them inside the library; nobody
# interposes ours, so the library keeps the code a static build had (GCC manual,
# -fno-semantic-interposition).
target_compile_options(bimloc_localizer PRIVATE $<$<CXX_COMPILER_ID:GNU,Clang>:-fno-semantic-interposition>)
# The public headers are C++17 (std::optional): a consumer's target gets at least that.
target_compile_features(bimloc_localizer PUBLIC cxx_std_17)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/localizer/include/bimloc
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.hpp")
install(TARGETS bimloc_localizer
        EXPORT bimlocTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT bimlocTargets
        FILE bimlocTargets.cmake
        NAMESPACE bimloc::
        DESTINATION ${BIMLOC_CMAKE_INSTALL_DIR})

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/bimlocConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/bimlocConfig.cmake
                              INSTALL_DESTINATION ${BIMLOC_CMAKE_INSTALL_DIR})
# 0.x: any 0.y satisfies find_package(bimloc 0.1); a 1.0 would not.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/bimlocConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION}
                                 COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/bimlocConfig.cmake ${PROJECT_BINARY_DIR}/bimlocConfigVersion.cmake
        DESTINATION ${BIMLOC_CMAKE_INSTALL_DIR})

# pkg-config: the .pc names absolute paths, so its prefix is the one installed into, known only
# at install time (`cmake --install --prefix ANY` overrides CMAKE_INSTALL_PREFIX there).
set(BIMLOC_PC_PREFIX "@BIMLOC_PC_PREFIX@")  # kept for the install step below
configure_file(${CMAKE_CURRENT_LIST_DIR}/bimloc.pc.in ${PROJECT_BINARY_DIR}/bimloc.pc.in @ONLY)
install(CODE "set(BIMLOC_PC_PREFIX \"\${CMAKE_INSTALL_PREFIX}\")
  configure_file(\"${PROJECT_BINARY_DIR}/bimloc.pc.in\" \"${PROJECT_BINARY_DIR}/bimloc.pc\" @ONLY)")
install(FILES ${PROJECT_BINARY_DIR}/bimloc.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

if(TARGET bimloc)
  # Installed, the command finds the localizer next door (lib/ beside bin/), and IFC++ as before.
  set_property(TARGET bimloc APPEND PROPERTY INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
  install(TARGETS bimloc RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
