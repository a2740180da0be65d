# cmake -DFILE=<json file> -DKEYS="a;b;c.d" -P expect_json_keys.cmake
# Fails unless FILE is a JSON object holding every key (dots descend into objects).
file(READ "${FILE}" json)
foreach(key IN LISTS KEYS)
  string(REPLACE "." ";" path "${key}")
  string(JSON value ERROR_VARIABLE error GET "${json}" ${path})
  if(error)
    message(FATAL_ERROR "${FILE}: no key '${key}' (${error})")
  endif()
endforeach()
