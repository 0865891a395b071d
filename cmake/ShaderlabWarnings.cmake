# Warnings for our own targets only; dependencies come in through imported targets, whose
# include directories CMake marks SYSTEM, so their headers do not trip -Werror.
function(shaderlab_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wshadow -Wnon-virtual-dtor -Wpedantic)
  if(SHADERLAB_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
