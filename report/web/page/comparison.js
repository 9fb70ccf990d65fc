// The comparison page (bench compare --html): verdict counts, pairs on one side only, differing
// settings, the verdict table, and per problem side-by-side box plots of base and new runs.
"use strict";

(function comparisonReport() {
  const data = REPORT;
  const comparison = data.comparison;
  const slug = text => text.replace(/[^A-Za-z0-9]+/g, "-");
  const VERDICT_COLOURS = {worse: "#d62728", better: "#2ca02c", same: "#7f7f7f", "not comparable": "#bcbd22"};
  const SIDE_COLOURS = {base: "#1f77b4", new: "#ff7f0e"};
  const metricLabel = key => key === "success_rate" ? "success rate" : key === "-" ? "–"
                           : (data.metrics.find(m => m.key === key) || {label: key}).label;
  const verdictBadge = verdict => el("span", {class: "verdict verdict-" + slug(verdict),
                                              style: "color:" + VERDICT_COLOURS[verdict], text: verdict});

  function verdictSection() {
    const section = addSection("verdicts", "Verdicts",
      "Base is the reference, new the campaign judged. Zero-variance results (the arc planner) are compared exactly within the " +
      "tolerance; sampling planners with Fisher's exact test (success) and the Mann–Whitney U test (metrics), Holm-adjusted over " +
      "the table, flagged only when also at least the minimum effect. See docs/benchmarks.md, \"Comparing campaigns\".");
    const counts = comparison.counts;
    const options = comparison.options;
    const entries = [
      ["base", comparison.base],
      ["new", comparison.new],
      ["verdicts", counts.worse + " worse, " + counts.better + " better, " + counts.same + " same, " + counts.not_comparable + " not comparable"],
      ["thresholds", "alpha " + options.alpha + " (Holm), minimum effect " + formatNumber(100 * options.min_effect) + " %, exact tolerance " +
                     options.tolerance + ", solve-time floor " + options.solve_time_floor_s + " s"],
    ];
    section.appendChild(el("dl", {class: "settings", id: "verdict-summary"},
      entries.flatMap(([key, value]) => [el("dt", {text: key}), el("dd", {text: String(value)})])));
    const oneSided = comparison.only_in_base.map(pair => "only in base: " + pair)
      .concat(comparison.only_in_new.map(pair => "only in new: " + pair));
    if (oneSided.length) {
      section.appendChild(el("h3", {text: "On one side only"}));
      section.appendChild(el("ul", {id: "one-sided"}, oneSided.map(text => el("li", {text}))));
    }
    if (comparison.settings.length) {
      section.appendChild(el("h3", {text: "Different settings"}));
      const rows = comparison.settings.map((s, i) => Object.assign({key: "setting-" + i}, s));
      section.appendChild(sortableTable("settings-table", [
        {label: "setting", text: true, value: row => row.setting, cell: row => row.setting},
        {label: "base", text: true, value: row => row.base, cell: row => row.base},
        {label: "new", text: true, value: row => row.new, cell: row => row.new},
        {label: "where", text: true, value: row => String(row.pairs), cell: row => row.pairs === "all" ? "every pair" : row.pairs.join(", ")},
      ], rows));
    }
    const notes = missingNotes(data.missing);
    if (notes) section.appendChild(notes);
  }

  function tableSection() {
    const section = addSection("table", "Verdict table",
      "One row per problem, planner and metric (success rate first). Values: success rate, the exact value, or the median of the " +
      "successful runs; effect: new/base − 1 (success rate: difference in percentage points). Click a header to sort.");
    const rows = comparison.rows.map((row, index) => Object.assign({key: "row-" + index}, row));
    const value = (row, v) => v === null ? null : (row.metric === "success_rate" ? 100 * v : v);
    section.appendChild(sortableTable("comparison-table", [
      {label: "problem", text: true, value: row => row.problem, cell: row => row.problem},
      {label: "planner", text: true, value: row => row.planner, cell: row => row.planner},
      {label: "metric", text: true, value: row => metricLabel(row.metric), cell: row => metricLabel(row.metric)},
      {label: "n", title: "runs (success rate) or successful runs (metrics), base → new", value: row => row.new_n,
       cell: row => row.base_n + " → " + row.new_n},
      {label: "base", value: row => value(row, row.base), cell: row => formatNumber(value(row, row.base), 7) + (row.metric === "success_rate" && row.base !== null ? " %" : "")},
      {label: "new", value: row => value(row, row.new), cell: row => formatNumber(value(row, row.new), 7) + (row.metric === "success_rate" && row.new !== null ? " %" : "")},
      {label: "effect", value: row => row.effect, cell: row => row.effect === null ? "–"
        : (row.effect >= 0 ? "+" : "") + formatNumber(100 * row.effect, 3) + (row.metric === "success_rate" ? " pp" : " %")},
      {label: "test", text: true, value: row => row.test, cell: row => row.test},
      {label: "p", value: row => row.p},
      {label: "p (Holm)", value: row => row.p_holm},
      {label: "verdict", text: true, value: row => row.verdict, cell: row => verdictBadge(row.verdict)},
      {label: "note", text: true, value: row => row.note, cell: row => row.note},
    ], rows));
  }

  // Per problem: one plot per metric with a base and a new box for every planner of both campaigns.
  function boxPlotSection() {
    const problems = Object.keys(data.values).filter(problem =>
      Object.values(data.values[problem]).some(sides => sides.base && sides.new));
    if (problems.length === 0) return;
    const section = addSection("boxplots", "Side by side",
      "Every successful run as a point over its box, base (blue) next to new (orange) for each planner present in both; the " +
      "title of each planner's group carries its verdict for that metric. Drag to zoom, double-click to reset.");
    const verdictOf = (problem, planner, metric) => {
      const row = comparison.rows.find(r => r.problem === problem && r.planner === planner && r.metric === metric);
      return row ? row.verdict : "";
    };
    selectablePlotGrid(section, "problem", problems.map(p => ({value: p, label: p})), (problem, grid) => {
      const planners = Object.keys(data.values[problem]).filter(name => data.values[problem][name].base && data.values[problem][name].new).sort();
      for (const metric of data.metrics) {
        const container = el("div", {class: "plot comparison-boxplot", id: "compare-box-" + slug(metric.key), "data-problem": problem});
        grid.appendChild(container);
        const traces = ["base", "new"].map(side => {
          const x = [], y = [];
          for (const planner of planners) {
            for (const v of data.values[problem][planner][side][metric.key]) {
              x.push(planner + " — " + verdictOf(problem, planner, metric.key));
              y.push(v);
            }
          }
          return {type: "box", name: side, x, y, boxpoints: "all", jitter: 0.3, pointpos: 0, marker: {color: SIDE_COLOURS[side], size: 4},
                  line: {width: 1.2}, hovertemplate: side + " %{x}<br>" + metric.label + " = %{y}<extra></extra>"};
        });
        plot(container, traces, {title: {text: metric.label + (metric.lower_is_better ? " (lower is better)" : " (higher is better)"),
                                         font: {size: 14}},
                                 boxmode: "group", xaxis: {tickangle: -30, automargin: true}, yaxis: {zeroline: false, automargin: true},
                                 margin: {l: 60, r: 14, t: 64, b: 50}, legend: {orientation: "h", x: 0, y: 1.02, yanchor: "bottom"}});
      }
    });
  }

  verdictSection();
  tableSection();
  boxPlotSection();
  document.getElementById("loading").remove();
  window.arcplanReport.ready = true;
})();
