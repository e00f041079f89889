# CLI11 from the host (/usr/include/CLI), header only: see host_headers.cmake.
include(${CMAKE_CURRENT_LIST_DIR}/host_headers.cmake)
springlab_host_headers(CLI11::CLI11 CLI)
