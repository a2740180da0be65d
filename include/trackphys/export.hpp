#pragma once

/// Marks the public API. The library is built with hidden visibility, so only what carries
/// this mark is exported from a shared build (static builds ignore it).
#define TRACKPHYS_API __attribute__((visibility("default")))
