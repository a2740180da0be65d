# The track part's sources: target_sources(trackphys PRIVATE track/...).
