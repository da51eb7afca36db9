// The trace types the scan report draws (crates/rtw-py/python/rtw/report_assets/report.js):
// scatter (in core), bar, scattergl, scatter3d, parcoords, parcats.
'use strict';
var Plotly = require('plotly.js/lib/core');
Plotly.register([
    require('plotly.js/lib/bar'),
    require('plotly.js/lib/scattergl'),
    require('plotly.js/lib/scatter3d'),
    require('plotly.js/lib/parcoords'),
    require('plotly.js/lib/parcats'),
]);
module.exports = Plotly;
