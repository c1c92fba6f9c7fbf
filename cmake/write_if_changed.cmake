# gpfd_write_if_changed(PATH TEXT): writes TEXT to PATH only when it differs, so that files
# regenerated at every build trigger no rebuild when their content is unchanged.
function(gpfd_write_if_changed path text)
  if(EXISTS ${path})
    file(READ ${path} old)
  else()
    set(old "")
  endif()
  if(NOT old STREQUAL text)
    file(WRITE ${path} "${text}")
  endif()
endfunction()
