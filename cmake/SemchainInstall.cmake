# `cmake --install build --prefix P`: the program and the files it ships, laid out as a Debian or
# catkin install would lay them out:
#   P/bin/semchain
#   P/lib/semchain/semchain_ros                (ROS's place for a package's nodes, when built)
#   P/share/semchain/{config,models,worlds}    (config/ros holds the launch and RViz files)
#   P/share/semchain/package.xml, P/.catkin    (when the node is built: rosrun and roslaunch find
#                                               the package with P on CMAKE_PREFIX_PATH and P/share
#                                               on ROS_PACKAGE_PATH)
# The programs find the shipped files in ../share/semchain relative to themselves
# (src/core/data_path.h), so a prefix works wherever it is moved.
#
# The build tree gets the same layout: build/share/semchain links to the source tree's folders,
# so build/apps/semchain and build/src/ros/semchain_ros find them as the installed programs do.
# No binary carries the source tree's path: what the tests run is what gets installed.

set(SEMCHAIN_DATA_FOLDERS config models worlds)

function(semchain_link_build_tree_data)
  set(share ${PROJECT_BINARY_DIR}/share/semchain)
  file(MAKE_DIRECTORY ${share})
  foreach(folder IN LISTS SEMCHAIN_DATA_FOLDERS)
    # Links, not copies: an edited config or world is seen without re-running CMake.
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${share}/${folder} SYMBOLIC COPY_ON_ERROR)
  endforeach()
endfunction()

# One version for CMake and ROS: package.xml must say project(VERSION).
function(semchain_check_package_version)
  file(READ ${PROJECT_SOURCE_DIR}/package.xml package_xml)
  string(REGEX MATCH "<version>([^<]*)</version>" _ "${package_xml}")
  if(NOT CMAKE_MATCH_1 STREQUAL PROJECT_VERSION)
    message(FATAL_ERROR "package.xml says version ${CMAKE_MATCH_1}, CMakeLists.txt's project() "
                        "${PROJECT_VERSION}: make them the same")
  endif()
endfunction()

semchain_check_package_version()
semchain_link_build_tree_data()

install(TARGETS semchain RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(folder IN LISTS SEMCHAIN_DATA_FOLDERS)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${folder} DESTINATION ${CMAKE_INSTALL_DATADIR}/semchain)
endforeach()
if(TARGET semchain_ros)
  install(TARGETS semchain_ros RUNTIME DESTINATION lib/semchain)  # catkin's, not multiarch
  install(FILES ${PROJECT_SOURCE_DIR}/package.xml DESTINATION ${CMAKE_INSTALL_DATADIR}/semchain)
  # catkin's mark of an install prefix (empty: no source spaces); ROS's tools look for a
  # package's nodes in P/lib/<package> only in prefixes that carry it.
  install(CODE "file(TOUCH \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/.catkin\")")
endif()
