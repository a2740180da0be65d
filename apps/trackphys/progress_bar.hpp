#pragma once

namespace trackphys::cli {

/// A progress bar on stderr, only when stderr is a terminal (never in logs or CI).
class ProgressBar {
  public:
    /// total: what `done` reaches at the end (laps, seconds...).
    explicit ProgressBar(double total);
    ~ProgressBar();
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    /// Redraws when the whole percentage changed, with a speed beside it.
    void show(double done, double speed_kmh);

  private:
    double total_;
    bool enabled_;
    int last_ = -1;
};

}  // namespace trackphys::cli
