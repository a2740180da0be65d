#pragma once

namespace trackphys::cli {

/// A progress bar on stderr, only when stderr is a terminal (never in logs or CI).
class ProgressBar {
  public:
    /// total: what `done` reaches at the end (laps, seconds, colliders...).
    explicit ProgressBar(double total);
    ~ProgressBar();
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    /// Redraws when the whole percentage changed, with a speed beside it.
    void show(double done, double speed_kmh);

    /// Redraws when the whole percentage changed, with the count beside it ("1234 of 3000
    /// colliders" for unit "colliders").
    void show_count(double done, const char* unit);

  private:
    /// Whether the bar is on and `done` changes its whole percentage, which it then keeps.
    bool advances(double done);
    void draw(const char* note) const;

    double total_;
    bool enabled_;
    int last_ = -1;
};

}  // namespace trackphys::cli
