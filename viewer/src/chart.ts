// A strip chart of one series over the whole drive, with a cursor at the current time;
// clicking or dragging on it seeks. Each pixel column draws the min..max of its frames, so
// a 60,000-update drive costs the same as a short one.

export interface Series {
  label: string;
  unit: string;
  colour: string;
  values: ArrayLike<number>;
}

export class Chart {
  readonly canvas = document.createElement("canvas");
  private series: Series | null = null;
  private columns: { min: Float32Array; max: Float32Array; low: number; high: number; peak: number } | null = null;
  private cursor = 0;
  /** The series drawn once per size and series; each frame copies it and adds the cursor. */
  private readonly plot = document.createElement("canvas");

  constructor(
    private readonly time: Float64Array,
    private readonly onSeek: (t: number) => void,
  ) {
    this.canvas.className = "chart";
    const seek = (e: PointerEvent) => {
      const box = this.canvas.getBoundingClientRect();
      const x = Math.min(Math.max((e.clientX - box.left) / box.width, 0), 1);
      this.onSeek(this.time[0] + x * (this.time[this.time.length - 1] - this.time[0]));
    };
    this.canvas.addEventListener("pointerdown", (e) => {
      this.canvas.setPointerCapture(e.pointerId);
      seek(e);
    });
    this.canvas.addEventListener("pointermove", (e) => {
      if (this.canvas.hasPointerCapture(e.pointerId)) seek(e);
    });
  }

  show(series: Series | null): void {
    this.series = series;
    this.columns = null;
    this.draw();
  }

  setCursor(frame: number): void {
    this.cursor = frame;
    this.draw();
  }

  private summarise(width: number): void {
    const values = this.series!.values;
    const n = values.length;
    const min = new Float32Array(width).fill(Infinity);
    const max = new Float32Array(width).fill(-Infinity);
    let low = Infinity;
    let high = -Infinity;
    for (let i = 0; i < n; ++i) {
      const x = Math.min(Math.floor((i / n) * width), width - 1);
      const v = values[i];
      if (v < min[x]) min[x] = v;
      if (v > max[x]) max[x] = v;
      if (v < low) low = v;
      if (v > high) high = v;
    }
    // A few spikes (the machine doing something else) would flatten the rest: the scale
    // stops at the 99.5th percentile and taller columns are clipped.
    const sorted = Float32Array.from(values as ArrayLike<number>).sort();
    const top = sorted[Math.floor(0.995 * (n - 1))] * 1.25;
    this.columns = { min, max, low: Math.min(low, 0), high: Math.max(Math.min(high, top), 1e-9), peak: high };
  }

  draw(): void {
    const ratio = window.devicePixelRatio || 1;
    const width = Math.max(Math.round(this.canvas.clientWidth * ratio), 1);
    const height = Math.max(Math.round(this.canvas.clientHeight * ratio), 1);
    if (this.canvas.width !== width || this.canvas.height !== height) {
      this.canvas.width = this.plot.width = width;
      this.canvas.height = this.plot.height = height;
      this.columns = null;
    }
    const g = this.canvas.getContext("2d")!;
    g.clearRect(0, 0, width, height);
    if (!this.series || this.series.values.length === 0) return;
    if (!this.columns) this.plotSeries(width, height);
    g.drawImage(this.plot, 0, 0);
    const n = this.series.values.length;
    const cx = Math.round((this.cursor / Math.max(n - 1, 1)) * (width - 1));
    g.fillStyle = "#ffffff";
    g.fillRect(cx, 0, Math.max(ratio, 1), height);
    g.font = `${11 * ratio}px system-ui, sans-serif`;
    g.fillStyle = "#e8e8e8";
    const value = this.series.values[Math.min(this.cursor, n - 1)];
    g.fillText(
      `${this.series.label} ${value.toFixed(1)} ${this.series.unit}   (max ${this.columns!.peak.toFixed(0)})`,
      6 * ratio,
      13 * ratio,
    );
  }

  private plotSeries(width: number, height: number): void {
    this.summarise(width);
    const { min, max, low, high } = this.columns!;
    const y = (v: number) => Math.max(height - 2 - ((v - low) / (high - low)) * (height - 4), 0);
    const g = this.plot.getContext("2d")!;
    g.clearRect(0, 0, width, height);
    g.fillStyle = this.series!.colour;
    for (let x = 0; x < width; ++x) {
      if (min[x] > max[x]) continue;
      const top = y(max[x]);
      g.fillRect(x, top, 1, Math.max(y(min[x]) - top, 1));
    }
  }
}
