# The io part's sources: target_sources(trackphys PRIVATE io/...).
