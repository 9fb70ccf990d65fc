// The campaign report: settings and links, the ranking tables, box plots per metric and problem,
// TCP speed profiles and the 3D views of the plot problems.
"use strict";

(function campaignReport() {
  const data = REPORT;
  const problems = Object.keys(data.runs);
  const ranking = data.ranking;
  // Colours follow the overall ranking (best first), else the planners' names.
  const allPlanners = ranking ? ranking.planners.map(p => p.name)
                              : [...new Set(problems.flatMap(problem => Object.keys(data.runs[problem])))].sort();
  const colours = colourMap(allPlanners);
  const swatch = name => el("span", {}, [el("span", {class: "swatch", style: "background:" + colours[name]}), name]);
  const slug = text => text.replace(/[^A-Za-z0-9]+/g, "-");

  function settingsSection() {
    const section = addSection("settings", "Run settings",
      "What was run and with which versions; the files behind this report are linked below (relative to this file).");
    const campaign = data.settings.campaign || {};
    const experiment = data.settings.experiments[0] || {};
    const entries = [
      ["suite", campaign.suite || experiment.suite],
      ["problems", problems.length + " (" + problems.join(", ") + ")"],
      ["planners", allPlanners.length + " (" + allPlanners.join(", ") + ")"],
      ["runs per planner and problem", campaign.runs],
      ["time limit per run", campaign.time_limit !== undefined ? campaign.time_limit + " s" : experiment.timelimit && experiment.timelimit + " s"],
      ["TCP speed limit v_max", (campaign.v_max || experiment.vmax) && (campaign.v_max || experiment.vmax) + " m/s"],
      ["job seeds", data.settings.experiments.filter(e => e.jobseed !== undefined).length ? "per job, from (suite, problem, planner); see the database's experiments.jobseed" : null],
      ["generator seed", experiment.generatorseed],
      ["versions", ["arcplanversion", "omplversion", "fclversion", "eigenversion"].filter(k => experiment[k])
                     .map(k => k.replace("version", "") + " " + experiment[k]).join(", ") || experiment.version],
      ["machine", [experiment.hostname, experiment.cpuinfo && experiment.cpuinfo.split("\n")[0]].filter(Boolean).join(" — ")],
      ["database", data.source.database],
    ].filter(([, value]) => value !== undefined && value !== null && value !== "");
    section.appendChild(el("dl", {class: "settings"}, entries.flatMap(([key, value]) => [el("dt", {text: key}), el("dd", {text: String(value)})])));
    if (data.links.length) {
      section.appendChild(el("h3", {text: "Files"}));
      section.appendChild(el("ul", {class: "links"}, data.links.map(link => el("li", {}, [el("a", {href: link.href, text: link.label}), " — " + link.href]))));
    }
    const notes = missingNotes(data.missing);
    if (notes) section.appendChild(notes);
  }

  // Columns of a ranking table: rank, planner, (overall: mean rank, problems, 1st), success, every metric's median.
  function standingColumns(overall) {
    const columns = [
      {label: "rank", value: row => row.rank},
      {label: "planner", text: true, value: row => row.name, cell: row => swatch(row.name)},
    ];
    if (overall) {
      columns.push({label: "mean rank", title: "mean of the per-problem ranks", value: row => row.mean_rank});
      columns.push({label: "problems", value: row => row.problems});
      columns.push({label: "1st", title: "problems where it ranked first", value: row => row.first_places});
    }
    columns.push({label: "success", title: "successful runs / runs", value: row => row.success_rate,
                  cell: row => percent(row.success_rate) + " (" + row.solved + "/" + row.runs + ")"});
    for (const attribute of data.attributes) {
      columns.push({label: attribute.label, title: "median over successful runs; hover a cell for min, mean, max",
                    value: row => row[attribute.key] ? row[attribute.key].median : null,
                    cell: row => {
                      const summary = row[attribute.key];
                      if (!summary) return "–";
                      return el("span", {title: "min " + formatNumber(summary.min) + ", mean " + formatNumber(summary.mean) +
                                                ", max " + formatNumber(summary.max) + " (" + summary.count + " runs)",
                                         text: formatNumber(summary.median)});
                    }});
    }
    return columns;
  }

  // Without arcplan's columns: successes and the median of every run attribute, per planner.
  function plainRows(problemNames) {
    return allPlanners.map(name => {
      const row = {key: name, name, runs: 0, solved: 0};
      const values = {};
      for (const problem of problemNames) {
        const runs = data.runs[problem][name];
        if (!runs) continue;
        row.runs += runs.solved.length;
        row.solved += runs.solved.reduce((a, b) => a + b, 0);
        for (const attribute of data.attributes) values[attribute.key] = (values[attribute.key] || []).concat(runs.values[attribute.key]);
      }
      row.success_rate = row.runs ? row.solved / row.runs : 0;
      for (const attribute of data.attributes) row[attribute.key] = {median: median(values[attribute.key] || []), count: (values[attribute.key] || []).length};
      return row;
    }).filter(row => row.runs > 0);
  }

  function rankingSection() {
    const section = addSection("ranking", "Ranking",
      ranking ? "Per problem, planners are ordered by success rate, then by the median execution time at the TCP speed limit over all runs " +
                "(a failed run counts as infinitely slow); the overall rank is the mean of the per-problem ranks. Metric columns show " +
                "the median over successful runs — hover a cell for min, mean and max, click a header to sort."
              : "This database has no arcplan metrics, so planners are not ranked: the table counts successes (OMPL's 'solved') and " +
                "shows the median of each run attribute. Click a header to sort.");
    const withKeys = rows => rows.map(row => Object.assign({key: row.name}, row));
    section.appendChild(el("h3", {text: "Overall"}));
    if (ranking) {
      section.appendChild(sortableTable("ranking-overall", standingColumns(true), withKeys(ranking.planners)));
      for (const family of ranking.families || []) {
        section.appendChild(el("h3", {text: "Family " + family.name + " (" + family.problems + " problems)"}));
        section.appendChild(sortableTable("ranking-family-" + slug(family.name), standingColumns(true), withKeys(family.planners)));
      }
    } else {
      section.appendChild(sortableTable("ranking-overall", standingColumns(false).filter(c => c.label !== "rank"), plainRows(problems)));
    }
    const perProblem = el("details", {open: problems.length <= 4}, [el("summary", {text: "Per problem (" + problems.length + ")"})]);
    for (const problem of problems) {
      perProblem.appendChild(el("h3", {text: problem}));
      const rows = ranking ? withKeys(ranking.problems.find(p => p.name === problem).planners) : plainRows([problem]);
      const columns = ranking ? standingColumns(false) : standingColumns(false).filter(c => c.label !== "rank");
      perProblem.appendChild(sortableTable("ranking-problem-" + slug(problem), columns, rows));
    }
    section.appendChild(perProblem);
  }

  // One box per planner for every attribute of the chosen problem; every run a point, hover names it.
  function boxPlotSection() {
    const section = addSection("boxplots", "Runs per metric",
      "Every run of every planner as a point over its box (median, quartiles, whiskers at 1.5 IQR). Hover a point for its run; " +
      "drag to zoom, double-click to reset. Failed runs have no metrics and are counted in the x labels (successes/runs).");
    selectablePlotGrid(section, "problem", problems.map(p => ({value: p, label: p})), (problem, grid) => {
      for (const attribute of data.attributes) {
        const container = el("div", {class: "plot boxplot", id: "box-" + slug(attribute.key), "data-problem": problem});
        grid.appendChild(container);
        const planners = allPlanners.filter(name => data.runs[problem][name]);
        const traces = planners.map(name => {
          const runs = data.runs[problem][name];
          const points = runs.values[attribute.key].map((value, run) => ({value, run})).filter(p => p.value !== null);
          const solved = runs.solved.reduce((a, b) => a + b, 0);
          return {type: "box", name: name + " (" + solved + "/" + runs.solved.length + ")", y: points.map(p => p.value),
                  text: points.map(p => "run " + p.run), boxpoints: "all", jitter: 0.35, pointpos: 0,
                  marker: {color: colours[name], size: 5}, line: {width: 1.2},
                  hovertemplate: "<b>" + name + "</b> %{text}<br>" + attribute.label + " = %{y}<extra></extra>"};
        });
        plot(container, traces, {title: {text: attribute.label, font: {size: 14}}, showlegend: false,
                                 xaxis: {tickangle: -40, automargin: true}, yaxis: {zeroline: false, automargin: true}});
      }
    });
  }

  function pathSections() {
    const plotted = Object.keys(data.paths);
    if (plotted.length === 0) return;
    const speeds = addSection("speed", "TCP speed profiles",
      "The TCP speed along each planner's median run (by execution time) after time scaling, with the speed limit v_max. " +
      "Drag to zoom into a ramp or a plateau, double-click to reset; click a legend entry to hide a planner.");
    const views = addSection("view3d", "3D view",
      "The scene's obstacles (small ones red, tables grey; bodies the robot holds orange), start (green) and goal (black), each planner's TCP path in its colour, and the robot (its tool and gripper included) at the " +
      "planned joint states. Drag to orbit, scroll to zoom, right-drag to pan; move the time slider or press play to run the " +
      "time-scaled motion, choose which planner's motion the arm shows, tick planners on or off.");
    const byRank = (a, b) => allPlanners.indexOf(a.name) - allPlanners.indexOf(b.name);
    for (const problem of plotted) {
      const paths = data.paths[problem];
      paths.planners.sort(byRank);  // legends, toggles and the arm's default planner in ranking order
      const vmax = paths.scene.vmax_mps;
      const traces = paths.planners.map(planner => ({type: "scatter", mode: "lines", name: planner.name, x: planner.t, y: planner.speed,
                                                     line: {color: colours[planner.name], width: 1.6},
                                                     hovertemplate: planner.name + ": %{y:.4f} m/s at %{x:.3f} s<extra></extra>"}));
      const longest = Math.max(...paths.planners.map(p => p.t[p.t.length - 1]));
      traces.push({type: "scatter", mode: "lines", name: "v_max " + vmax + " m/s", x: [0, longest], y: [vmax, vmax],
                   line: {color: "#d62728", dash: "dash", width: 1.4}, hoverinfo: "name"});
      speeds.appendChild(el("h3", {text: problem}));
      const container = el("div", {class: "plot wide speed-plot", id: "speed-" + slug(problem)});
      speeds.appendChild(container);
      plot(container, traces, {xaxis: {title: {text: "time (s)"}}, yaxis: {title: {text: "TCP speed (m/s)"}, rangemode: "tozero"},
                               legend: {font: {size: 11}}});

      views.appendChild(el("h3", {text: problem}));
      const holder = el("div", {class: "robot-view"});
      views.appendChild(holder);
      const view = createRobotView(holder, problem, paths, data.robots[paths.robot], colours);
      if (view) window.arcplanReport.views.push(view);
    }
  }

  settingsSection();
  rankingSection();
  boxPlotSection();
  pathSections();
  document.getElementById("loading").remove();
  window.arcplanReport.ready = true;
})();
