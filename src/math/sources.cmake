target_sources(trackphys PRIVATE
  math/symmetric_eigen.cpp)
