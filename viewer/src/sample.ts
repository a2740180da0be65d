// Where a time falls between recorded updates, for interpolating poses at any frame rate.

/** Frame `index` and the fraction (0..1) of the way to the next one. */
export interface Sample {
  index: number;
  fraction: number;
}

/** The sample at time t (clamped to the recording's span), by binary search over time. */
export function sampleAt(time: Float64Array, t: number): Sample {
  const last = time.length - 1;
  if (!(t > time[0])) return { index: 0, fraction: 0 };
  if (t >= time[last]) return { index: last, fraction: 0 };
  let lo = 0;
  let hi = last; // time[lo] < t <= time[hi]
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (time[mid] < t) lo = mid;
    else hi = mid;
  }
  const fraction = (t - time[lo]) / (time[hi] - time[lo]);
  return fraction >= 1 ? { index: hi, fraction: 0 } : { index: lo, fraction };
}

/** values[index * stride + k] interpolated linearly towards the next frame. */
export function lerpAt(values: ArrayLike<number>, stride: number, k: number, s: Sample): number {
  const a = values[s.index * stride + k];
  if (s.fraction === 0) return a;
  return a + (values[(s.index + 1) * stride + k] - a) * s.fraction;
}
