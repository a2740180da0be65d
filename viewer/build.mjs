// Bundles the viewer (src/main.ts, three.js and all) into one minified script.
//   node build.mjs OUT.js       a script, for trying the viewer out
//   node build.mjs OUT.inc      the same as a C++ raw string literal, which the trackphys
//                               command includes (apps/trackphys/viewer_bundle.cpp)
// The page inlines the script, so it must not contain "</script" (it would end the
// element early): checked here rather than escaped, since esbuild already escapes it in
// string literals and anything else would be a bug to see.
import { build } from "esbuild";
import { writeFileSync } from "node:fs";

const out = process.argv[2];
if (!out) throw new Error("usage: node build.mjs OUT.js|OUT.inc");
const result = await build({
    entryPoints: [new URL("src/main.ts", import.meta.url).pathname],
    bundle: true,
    minify: true,
    format: "iife",
    target: "es2022",
    loader: { ".css": "text" },
    legalComments: "none",
    write: false,
    logLevel: "warning",
});
const script = result.outputFiles[0].text;
if (/<\/script/i.test(script)) throw new Error('the bundle contains "</script"');
const delimiter = "trackphys_js";
if (script.includes(`)${delimiter}"`)) throw new Error("the bundle contains the raw string's delimiter");
writeFileSync(out, out.endsWith(".inc") ? `R"${delimiter}(${script})${delimiter}"\n` : script);
