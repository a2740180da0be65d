// Reads the data `trackphys view` put into the page: base64 text in <script> elements of a
// non-JavaScript type, each zlib-compressed (docs/viewer.md, "The page").

// Chromium 140+ and Firefox 133+ decode base64 natively, several times faster.
const fromBase64 = (Uint8Array as unknown as { fromBase64?: (text: string) => Uint8Array }).fromBase64;

function base64Bytes(text: string): Uint8Array {
  if (fromBase64) return fromBase64(text.trim());
  // atob builds a string of the same length first; decoding directly halves the memory
  // and the time for a 10 MB recording.
  const code = new Uint8Array(128).fill(255);
  const alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  for (let i = 0; i < alphabet.length; ++i) code[alphabet.charCodeAt(i)] = i;
  const out = new Uint8Array(Math.floor((text.length * 3) / 4));
  let bits = 0;
  let count = 0;
  let n = 0;
  for (let i = 0; i < text.length; ++i) {
    const c = text.charCodeAt(i);
    const v = c < 128 ? code[c] : 255;
    if (v === 255) continue; // padding and whitespace
    bits = (bits << 6) | v;
    count += 6;
    if (count >= 8) {
      count -= 8;
      out[n++] = (bits >> count) & 0xff;
    }
  }
  return out.subarray(0, n);
}

/** Decompresses zlib data (what the C++ side's compress2 writes). */
export async function inflate(bytes: Uint8Array): Promise<ArrayBuffer> {
  const stream = new Blob([bytes as BlobPart]).stream().pipeThrough(new DecompressionStream("deflate"));
  return new Response(stream).arrayBuffer();
}

/** The element's payload, decoded; null when the page has no such element. */
export async function embeddedBytes(id: string): Promise<{ bytes: ArrayBuffer; element: HTMLElement } | null> {
  const element = document.getElementById(id);
  if (!element) return null;
  return { bytes: await inflate(base64Bytes(element.textContent ?? "")), element };
}
