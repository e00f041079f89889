include(/usr/share/eigen3/cmake/Eigen3ConfigVersion.cmake)
