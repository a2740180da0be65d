# The collision part's sources: target_sources(trackphys PRIVATE collision/...).
