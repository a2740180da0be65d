# cmake -DREADME=<README.md> -DFILE=<source> -P readme_quotes_file.cmake
# Fails unless README quotes FILE whole, as a fenced code block: the example a newcomer reads
# first is the one the package test builds and runs.
file(READ "${README}" readme)
file(READ "${FILE}" source)
get_filename_component(ext "${FILE}" LAST_EXT)
string(SUBSTRING "${ext}" 1 -1 language)
string(FIND "${readme}" "```${language}\n${source}```\n" at)
if(at EQUAL -1)
  message(FATAL_ERROR "${README} does not quote ${FILE} verbatim in a ```${language} block")
endif()
