# nlohmann/json from the host (/usr/include/nlohmann), header only: see host_headers.cmake.
include(${CMAKE_CURRENT_LIST_DIR}/host_headers.cmake)
springlab_host_headers(nlohmann_json::nlohmann_json nlohmann)
