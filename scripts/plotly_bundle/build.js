// plotly.js's own esbuild settings (node_modules/plotly.js/esbuild-config.js),
// minified, with entry.js's trace types only. Usage: node build.js OUT.js
const crypto = require('crypto');
const fs = require('fs');
const path = require('path');
const esbuild = require('esbuild');
const { environmentPlugin } = require('esbuild-plugin-environment');
const { glsl } = require('esbuild-plugin-glsl');

// A stylesheet becomes a script that adds it to the page once, as plotly.js's
// esbuild-plugin-inline-css does, but its id is the hash of its path inside
// this directory, not of the absolute path: the same bundle wherever it is built.
const inlineCss = {
    name: 'inline-css',
    setup(build) {
        build.onLoad({ filter: /\.css$/ }, (args) => {
            const id = crypto.createHash('sha256')
                .update(path.relative(__dirname, args.path).split(path.sep).join('/')).digest('hex');
            const css = JSON.stringify(fs.readFileSync(args.path, 'utf8'));
            return {
                contents: `(function(){ if (!document.getElementById("${id}")) { var e = document.createElement("style");`
                    + ` e.id = "${id}"; e.textContent = ${css}; document.head.appendChild(e); } })();`,
                loader: 'js',
            };
        });
    },
};
const version = require('plotly.js/package.json').version;

esbuild.build({
    entryPoints: [require.resolve('./entry.js')],
    outfile: process.argv[2],
    format: 'iife',
    globalName: 'Plotly',
    bundle: true,
    minify: true,
    legalComments: 'none',
    banner: { js: `/* plotly.js v${version} (bar, scatter, scattergl, scatter3d, parcoords, parcats), `
        + 'Copyright 2012-2026 Plotly, Inc., MIT license; built by rtw scripts/plotly_bundle.sh */' },
    sourcemap: false,
    plugins: [inlineCss, glsl({ minify: true }), environmentPlugin({ NODE_DEBUG: false })],
    alias: { regl: '@plotly/regl', stream: 'stream-browserify' },
    define: { global: 'window', 'define.amd': 'false' },
    target: 'es2016',
    logLevel: 'warning',
}).catch(() => process.exit(1));
