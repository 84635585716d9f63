// The page's style, inserted by the script: the replay file holds one script and one data block.
export const STYLE = `
html, body { margin: 0; height: 100%; background: #1e2329; color: #dde3ea;
  font: 13px system-ui, sans-serif; overflow: hidden; }
#mjarm-root { display: flex; flex-direction: column; height: 100%; }
#mjarm-main { flex: 1; display: flex; min-height: 0; }
#mjarm-view { flex: 1; position: relative; min-width: 0; }
#mjarm-view canvas { display: block; width: 100%; height: 100%; }
#mjarm-plots { width: 34%; max-width: 520px; overflow-y: auto; background: #fff; color: #222; }
#mjarm-plots.hidden { display: none; }
#mjarm-bar { display: flex; gap: 6px; align-items: center; padding: 6px 8px; background: #2a3038; }
#mjarm-bar button, #mjarm-bar select { background: #3a424d; color: #dde3ea; border: 1px solid #55606d;
  border-radius: 3px; padding: 2px 8px; }
#mjarm-scrub { flex: 1; }
#mjarm-time { font-variant-numeric: tabular-nums; min-width: 150px; text-align: right; }
#mjarm-phases { position: relative; height: 16px; background: #242a31; font-size: 11px; }
#mjarm-phases span { position: absolute; top: 1px; white-space: nowrap; border-left: 1px solid #8ab4f8;
  padding-left: 2px; color: #b8c4d0; }
#mjarm-phases .mjarm-event { position: absolute; top: 0; width: 3px; height: 16px; margin-left: -1px;
  background: #e8710a; cursor: help; }
#mjarm-phases .mjarm-result { background: #34a853; }
#mjarm-phases .mjarm-warning, #mjarm-phases .mjarm-divergence { background: #ea4335; }
#mjarm-bar label { white-space: nowrap; color: #b8c4d0; }
#mjarm-title { position: absolute; left: 8px; top: 6px; font-size: 12px; color: #b8c4d0; pointer-events: none; }
#mjarm-notes { position: absolute; left: 8px; top: 24px; max-width: 70%; font-size: 12px; color: #f0b040; pointer-events: none; }
`;

// The live view's panel (live.js): the viewer's sliders, mode and reset beside the 3D view.
export const LIVE_STYLE = `
#mjarm-panel { width: 290px; padding: 10px; overflow-y: auto; background: #2a3038; }
#mjarm-panel label { display: block; margin-top: 8px; color: #b8c4d0; }
#mjarm-panel input[type=range] { width: 100%; }
#mjarm-panel .value { float: right; font-family: monospace; }
#mjarm-panel button, #mjarm-panel select { background: #3a424d; color: #dde3ea;
  border: 1px solid #55606d; border-radius: 3px; padding: 2px 8px; margin-top: 8px; }
#mjarm-status { font-family: monospace; white-space: pre; margin-top: 12px; color: #b8c4d0; }
#mjarm-link.down { color: #ea4335; }
`;
