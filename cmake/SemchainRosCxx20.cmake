# ROS 1's generated message headers and ros/serialization.h (as Debian 12 and ROS Noetic ship
# them) name `Allocator::template rebind<T>::other`, which C++20 removed from std::allocator, so
# they do not compile in a C++20 project. The fix merged upstream (ros/gencpp#51,
# ros/roscpp_core#124) spells it `std::allocator_traits<Allocator>::template rebind_alloc<T>`,
# the same type. semchain_ros_cxx20_headers() writes copies of the affected headers with that
# fix into a directory of the build tree, to be searched before the system's; headers without
# the old spelling are used from where they are.

# semchain_ros_cxx20_headers(ROOT DEST): ROOT is the include root holding ros/serialization.h
# and the message packages (<name>_msgs/, <name>_srvs/); the fixed copies go under DEST.
function(semchain_ros_cxx20_headers root dest)
  file(GLOB headers RELATIVE ${root}
       ${root}/ros/serialization.h ${root}/*_msgs/*.h ${root}/*_srvs/*.h)
  set(count 0)
  foreach(header IN LISTS headers)
    file(READ ${root}/${header} text)
    string(FIND "${text}" "::template rebind<" position)
    if(position EQUAL -1)
      continue()
    endif()
    # Every use is 'typename ContainerAllocator::template rebind<X>::other' on one line.
    string(REPLACE "typename ContainerAllocator::template rebind<"
                   "typename std::allocator_traits<ContainerAllocator>::template rebind_alloc<"
                   text "${text}")
    string(REPLACE ">::other" ">" text "${text}")
    # The copy is in another directory: an include relative to the original's must name it.
    get_filename_component(directory ${header} DIRECTORY)
    string(REGEX REPLACE "#include \"([^\"/]+)\"" "#include <${directory}/\\1>" text "${text}")
    # CONFIGURE_DEPENDS-like behaviour: rewrite only when the content changes, so that a
    # reconfigure does not rebuild everything that includes a message.
    set(target ${dest}/${header})
    set(old "")
    if(EXISTS ${target})
      file(READ ${target} old)
    endif()
    if(NOT old STREQUAL text)
      file(WRITE ${target} "${text}")
    endif()
    math(EXPR count "${count} + 1")
  endforeach()
  if(count GREATER 0)
    message(STATUS "ROS 1: ${count} headers given the C++20 allocator fix in ${dest}")
  endif()
endfunction()
