// The replay clock: simulated time advanced by wall time times the rate while playing,
// clamped to the recording's span; stepping moves by whole recorded updates.

export const RATES = [0.25, 0.5, 1, 2, 4];

export class Playback {
  t: number;
  playing = false;
  rate = 1;

  constructor(
    readonly start: number,
    readonly end: number,
    readonly dt: number,
  ) {
    this.t = start;
  }

  /** Moves the clock on by a wall-clock interval (s); stops at the end. */
  advance(wallSeconds: number): void {
    if (!this.playing) return;
    this.t = Math.min(this.t + wallSeconds * this.rate, this.end);
    if (this.t >= this.end) this.playing = false;
  }

  seek(t: number): void {
    this.t = Math.min(Math.max(t, this.start), this.end);
  }

  /** Pauses and moves by n updates, landing on an update's time. */
  step(n: number): void {
    this.playing = false;
    const k = Math.round((this.t - this.start) / this.dt) + n;
    this.seek(this.start + k * this.dt);
  }

  toggle(): void {
    if (!this.playing && this.t >= this.end) this.t = this.start; // play again from the start
    this.playing = !this.playing;
  }
}
