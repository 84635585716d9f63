// The plots beside the 3D view (uPlot): the recording's figures on the replay's time base, with a
// cursor at the replay's time; a click on a plot moves the replay there.
import uPlot from 'uplot';
import uPlotStyle from 'uplot/dist/uPlot.min.css';

import {floats} from './decode.js';

const COLOURS =
    ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf'];

export function buildPlots(data, container, seek) {
  const plots = data.plots || [];
  if (plots.length === 0) {
    container.classList.add('hidden');
    return {cursor() {}, count: 0};
  }
  const style = document.createElement('style');
  style.textContent = uPlotStyle;
  document.head.appendChild(style);
  const time = floats(data.plot_time);
  const charts = [];
  for (const plot of plots) {
    const box = document.createElement('div');
    container.appendChild(box);
    const series = [{label: 't [s]'}];
    const columns = [time];
    plot.series.forEach((s, i) => {
      series.push(
          {label: s.label, stroke: COLOURS[i % COLOURS.length], width: 1, points: {show: false}});
      columns.push(floats(s.values));
    });
    const chart = new uPlot(
        {
          title: `${plot.title}${plot.unit ? ` [${plot.unit}]` : ''}`,
          width: Math.max(container.clientWidth - 16, 240),
          height: 170,
          series,
          scales: {x: {time: false}},
          legend: {show: plot.series.length <= 8},
          cursor: {drag: {x: false, y: false}},
        },
        columns, box);
    const line = document.createElement('div');
    line.style.cssText =
        'position:absolute;top:0;bottom:0;width:0;border-left:2px solid #e8710a;pointer-events:none';
    chart.over.appendChild(line);
    chart.over.addEventListener('click', (e) => seek(chart.posToVal(e.offsetX, 'x')));
    charts.push({chart, line});
  }
  return {
    count: charts.length,
    cursor(t) {
      for (const {chart, line} of charts) line.style.left = `${chart.valToPos(t, 'x')}px`;
    },
  };
}
