# The public C header compiles as strict C99 and a plain C program can use the library.
add_executable(capi_c_api_check ${CMAKE_CURRENT_SOURCE_DIR}/capi/c_api_check.c)
set_target_properties(capi_c_api_check PROPERTIES C_STANDARD 99 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF)
target_compile_options(capi_c_api_check PRIVATE -Wall -Wextra -Werror -pedantic)
target_link_libraries(capi_c_api_check PRIVATE macrocon)
add_test(NAME capi.c_api_check COMMAND capi_c_api_check)
