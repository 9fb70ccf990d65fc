// The model session report: the error after every step, measured vs predicted per channel with the
// worst windows, the residual against the signals, the diagnosis ranking with its explanations and
// the model-file lines that add the suggested effects.
"use strict";

(function modelReport() {
  const data = REPORT;
  const steps = (data.history && data.history.steps) || [];

  function overviewSection() {
    const section = addSection("overview", "Session",
      "A model-vs-measurements session (arcplan model compare / diagnose / fit with --out). Lower errors are better: " +
      "NRMSE is the RMS error divided by the standard deviation of the measured signal (1 = no better than its mean).");
    const last = steps[steps.length - 1];
    const entries = [["folder", data.source], ["steps", String(steps.length)],
                     ["model effects now", last ? last.effects.join(", ") : "–"],
                     ["overall NRMSE now", last ? formatNumber(last.train.overall_nrmse) + " on the fitted data" +
                       (last.validation ? ", " + formatNumber(last.validation.overall_nrmse) + " on the validation data" : "") : "–"]];
    section.appendChild(el("dl", {class: "settings"}, entries.flatMap(([k, v]) => [el("dt", {text: k}), el("dd", {text: v})])));
    const notes = missingNotes(data.missing);
    if (notes) section.appendChild(notes);
  }

  function historySection() {
    if (steps.length === 0) return;
    const section = addSection("history", "Error after every step",
      "The overall NRMSE after each compare or fit step of the session: it falls as the missing physical effects are added.");
    const labels = steps.map(step => step.step + ": " + step.command);
    const traces = [{type: "scatter", mode: "lines+markers", name: "fitted data", x: labels, y: steps.map(s => s.train.overall_nrmse)}];
    if (steps.some(s => s.validation)) {
      traces.push({type: "scatter", mode: "lines+markers", name: "validation data", x: labels,
                   y: steps.map(s => s.validation ? s.validation.overall_nrmse : null)});
    }
    const container = el("div", {class: "plot wide", id: "history-plot"});
    section.appendChild(container);
    plot(container, traces, {yaxis: {title: {text: "overall NRMSE"}, rangemode: "tozero"}, xaxis: {automargin: true}});
    const channels = Object.keys(steps[0].train.channels);
    const columns = [{label: "step", value: row => row.step}, {label: "command", text: true, value: row => row.command, cell: row => row.command},
                     {label: "overall NRMSE", value: row => row.train.overall_nrmse},
                     {label: "validation NRMSE", value: row => row.validation ? row.validation.overall_nrmse : null}]
      .concat(channels.map(channel => ({label: "RMSE " + channel, value: row => (row.validation || row.train).channels[channel].rmse})));
    section.appendChild(sortableTable("history-table", columns, steps.map(step => Object.assign({key: step.step}, step))));
  }

  // Windows to shade: only where the comparison analysed failures (its dataset) and on a time axis.
  function worstWindows(dataset) {
    const comparison = data.comparison;
    if (!comparison || !comparison.worst_windows) return [];
    if (comparison.failures_analysed_on !== dataset) return [];
    return comparison.worst_windows.filter(w => w.axis === "time_s");
  }

  // Events (moments the residual leaves its noise band and comes back, e.g. a push), where failures were analysed.
  function events(dataset) {
    const comparison = data.comparison;
    if (!comparison || !comparison.events || comparison.failures_analysed_on !== dataset) return [];
    return comparison.events;
  }

  function seriesSection() {
    const available = ["validation", "data"].filter(which => data.series[which]);
    if (available.length === 0) return;
    const section = addSection("series", "Measured vs predicted",
      "Each channel's measured signal and the model's prediction; the worst windows (largest normalised residual) are shaded. " +
      "Drag to zoom into a window, double-click to reset.");
    const options = available.map(which => ({value: which,
      label: which === "validation" ? "validation data (held out) — " + data.series[which].file : "fitted data — " + data.series[which].file}));
    selectablePlotGrid(section, "data", options, (which, grid) => {
      const shading = worstWindows(which).map(w => ({type: "rect", xref: "x", yref: "paper", x0: w.start, x1: w.end, y0: 0, y1: 1,
                                                     fillcolor: "#f4a261", opacity: 0.25, line: {width: 0}}))
        .concat(events(which).map(e => ({type: "rect", xref: "x", yref: "paper", x0: e.start_s, x1: e.end_s, y0: 0, y1: 1,
                                         fillcolor: "#d62728", opacity: 0.2, line: {width: 0}})));
      data.series[which].channels.forEach((channel, index) => {
        const container = el("div", {class: "plot series-plot", id: "series-" + index, "data-channel": channel.channel});
        grid.appendChild(container);
        plot(container, [
          {type: "scatter", mode: "lines", name: "measured", x: channel.time, y: channel.measured, line: {color: "#1f77b4", width: 1}},
          {type: "scatter", mode: "lines", name: "predicted", x: channel.time, y: channel.predicted, line: {color: "#ff7f0e", width: 1}},
        ], {title: {text: channel.channel, font: {size: 14}}, shapes: shading, xaxis: {title: {text: "time (s)"}},
            legend: {orientation: "h", y: -0.25}});
      });
    });

    const windows = data.comparison && data.comparison.worst_windows;
    if (windows && windows.length) {
      section.appendChild(el("h3", {text: "Worst windows (" + data.comparison.failures_analysed_on + " data)"}));
      section.appendChild(sortableTable("worst-windows", [
        {label: "start", value: w => w.start}, {label: "end", value: w => w.end}, {label: "NRMSE in window", value: w => w.nrmse},
        {label: "worst channel", text: true, value: w => w.worst_channel, cell: w => w.worst_channel}],
        windows.map((w, i) => Object.assign({key: i}, w))));
    }
    const found = data.comparison && data.comparison.events;
    if (found && found.length) {
      section.appendChild(el("h3", {text: "Events: moments the residual leaves its noise band and comes back (" +
                                          data.comparison.failures_analysed_on + " data, shaded red)"}));
      section.appendChild(sortableTable("events", [
        {label: "start (s)", value: e => e.start_s}, {label: "end (s)", value: e => e.end_s},
        {label: "joints", text: true, value: e => e.joints.join(","), cell: e => e.joints.join(", ")},
        {label: "peak (noise scales)", value: e => e.peak_scales},
        {label: "tool force (N)", value: e => (e.wrench_N ? Math.hypot(...e.wrench_N) : null)}],
        found.map((e, i) => Object.assign({key: i}, e))));
    }
  }

  function residualSection() {
    const which = ["validation", "data"].find(w => data.series[w]);
    if (!which) return;
    const channels = data.series[which].channels;
    const section = addSection("residual", "Residual against the signals",
      "The residual (measured − predicted) of one channel against each signal: a pattern (a step at zero speed, a slope with load, " +
      "a ripple with the angle) is an effect the model is missing.");
    selectablePlotGrid(section, "channel", channels.map((c, i) => ({value: String(i), label: c.channel})), (indexText, grid) => {
      const channel = channels[Number(indexText)];
      const residual = channel.measured.map((m, i) => m - channel.predicted[i]);
      for (const [signal, values] of Object.entries(channel.signals)) {
        const container = el("div", {class: "plot residual-plot", id: "residual-" + signal});
        grid.appendChild(container);
        plot(container, [{type: "scatter", mode: "markers", name: signal, x: values, y: residual,
                          marker: {size: 3, color: "#1f77b4", opacity: 0.5}}],
             {title: {text: "residual vs " + signal, font: {size: 14}}, xaxis: {title: {text: signal}},
              yaxis: {title: {text: "residual"}}, showlegend: false});
      }
    });
  }

  function diagnosisSection() {
    const diagnosis = data.diagnosis;
    if (!diagnosis) return;
    const section = addSection("diagnosis", "What is missing: the diagnosis",
      "Every catalogue effect not yet in the model, and terms found in the joints' signals, fitted to the residual and scored on " + diagnosis.heldout +
      ". The share of the held-out residual it removes ranks it; suggested effects pass the significance test.");
    section.appendChild(el("p", {class: "explanation summary", text: diagnosis.summary}));
    const ranking = diagnosis.ranking.map((candidate, index) => Object.assign({key: candidate.effect, rank: index + 1}, candidate));
    const container = el("div", {class: "plot wide", id: "diagnosis-plot"});
    section.appendChild(container);
    plot(container, [{type: "bar", orientation: "h", x: ranking.map(c => 100 * c.heldout_reduction), y: ranking.map(c => c.effect),
                      marker: {color: ranking.map(c => c.suggested ? "#2ca02c" : "#9aa5b1")},
                      hovertemplate: "%{y}: %{x:.1f} % of the held-out residual<extra></extra>"}],
         {xaxis: {title: {text: "held-out residual removed (%)"}}, yaxis: {autorange: "reversed", automargin: true}});
    section.appendChild(sortableTable("diagnosis-table", [
      {label: "rank", value: c => c.rank},
      {label: "effect", text: true, value: c => c.effect, cell: c => c.effect},
      {label: "joints", text: true, value: c => c.joints.join(","), cell: c => c.joints.join(", ") || "–"},
      {label: "held-out removed", value: c => c.heldout_reduction, cell: c => formatNumber(100 * c.heldout_reduction, 3) + " %"},
      {label: "score (ΔIC)", value: c => c.score},
      {label: "suggested", text: true, value: c => (c.suggested ? 1 : 0), cell: c => (c.suggested ? "yes" : "no")},
      {label: "explanation", text: true, value: c => c.explanation, cell: c => el("span", {class: "explanation", text: c.explanation || ""})},
    ], ranking));
    if (data.model_lines) {
      const lines = data.model_lines;
      section.appendChild(el("h3", {text: "Add the best suggestion"}));
      section.appendChild(el("p", {class: "intro", text: "In the model file, the effects line becomes:"}));
      section.appendChild(el("pre", {id: "model-lines", text: lines.effects_line}));
      if (lines.fit_command) {
        section.appendChild(el("p", {class: "intro", text: "or refit from the command line:"}));
        section.appendChild(el("pre", {text: lines.fit_command}));
      }
      if (lines.entries.length > 1) {
        section.appendChild(el("p", {class: "intro", text: "Every suggested entry, best first (add one at a time and diagnose again):"}));
        section.appendChild(el("pre", {id: "suggested-entries", text: lines.entries.join("\n")}));
      }
    }
    if (diagnosis.skipped && diagnosis.skipped.length) {
      section.appendChild(el("h3", {text: "Not tried"}));
      section.appendChild(el("ul", {}, diagnosis.skipped.map(text => el("li", {text}))));
    }
  }

  overviewSection();
  historySection();
  seriesSection();
  residualSection();
  diagnosisSection();
  document.getElementById("loading").remove();
  window.arcplanReport.ready = true;
})();
