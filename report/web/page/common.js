// Shared by both report kinds: the embedded data, DOM helpers, sortable tables, colours and the
// decoding of the base64 typed arrays arcplan writes. Plain browser JavaScript, no build step.
"use strict";

const REPORT = JSON.parse(document.getElementById("report-data").textContent);

// el("td", {class: "text", title: "..."}, ["text", childNode, ...])
function el(tag, attributes, children) {
  const node = document.createElement(tag);
  for (const [name, value] of Object.entries(attributes || {})) {
    if (value === undefined || value === null || value === false) continue;
    if (name === "text") node.textContent = value;
    else if (name.startsWith("on")) node.addEventListener(name.slice(2), value);
    else node.setAttribute(name, value === true ? "" : value);
  }
  for (const child of [].concat(children || [])) {
    if (child === null || child === undefined) continue;
    node.appendChild(typeof child === "string" ? document.createTextNode(child) : child);
  }
  return node;
}

// A top-level section with an entry in the contents line.
function addSection(id, title, intro) {
  const section = el("section", {id}, [el("h2", {text: title})]);
  if (intro) section.appendChild(el("p", {class: "intro", text: intro}));
  document.getElementById("report").appendChild(section);
  document.getElementById("contents").appendChild(el("a", {href: "#" + id, text: title}));
  return section;
}

function formatNumber(value, digits = 4) {
  if (value === null || value === undefined || Number.isNaN(value)) return "–";
  if (!Number.isFinite(value)) return value > 0 ? "∞" : "−∞";
  if (value !== 0 && (Math.abs(value) >= 1e5 || Math.abs(value) < 1e-3)) return value.toExponential(2);
  return String(Number(value.toPrecision(digits)));
}

function percent(rate) { return Math.round(100 * rate) + " %"; }

// A table whose columns sort on click (numbers numerically, missing values last).
// columns: [{label, title?, text?: bool, value: row => sortable value, cell?: row => string|Node}]
function sortableTable(id, columns, rows) {
  const body = el("tbody");
  const headCells = columns.map((column, index) =>
    el("th", {class: "sortable" + (column.text ? " text" : ""), title: column.title, text: column.label,
              onclick: () => sortBy(index)}));
  const table = el("table", {id, class: "sortable-table"}, [el("thead", {}, [el("tr", {}, headCells)]), body]);
  let sortedColumn = -1, ascending = true;
  function render() {
    body.replaceChildren(...rows.map(row => el("tr", {"data-key": row.key}, columns.map(column => {
      const content = column.cell ? column.cell(row) : formatNumber(column.value(row));
      return el("td", {class: column.text ? "text" : null}, [content]);
    }))));
  }
  function sortBy(index) {
    ascending = sortedColumn === index ? !ascending : true;
    sortedColumn = index;
    const value = columns[index].value;
    rows = rows.slice().sort((a, b) => {
      const x = value(a), y = value(b);
      const missingX = x === null || x === undefined || Number.isNaN(x), missingY = y === null || y === undefined || Number.isNaN(y);
      if (missingX || missingY) return missingX - missingY;
      const order = typeof x === "string" ? x.localeCompare(y) : x - y;
      return ascending ? order : -order;
    });
    headCells.forEach((cell, i) => cell.classList.toggle("sorted-asc", i === index && ascending));
    headCells.forEach((cell, i) => cell.classList.toggle("sorted-desc", i === index && !ascending));
    render();
  }
  render();
  return el("div", {class: "table-scroll"}, [table]);
}

function missingNotes(messages) {
  if (!messages || messages.length === 0) return null;
  return el("div", {class: "missing", id: "missing"}, [el("strong", {text: "Not in this report:"}),
    el("ul", {}, messages.map(message => el("li", {text: message})))]);
}

// Distinguishable colours, one per name in the given order (Tableau 10 then its lighter partners).
const PALETTE = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22",
                 "#17becf", "#aec7e8", "#ffbb78", "#98df8a", "#ff9896", "#c5b0d5", "#c49c94", "#f7b6d2", "#c7c7c7",
                 "#dbdb8d", "#9edae5"];
function colourMap(names) {
  const colours = {};
  names.forEach((name, index) => { colours[name] = PALETTE[index % PALETTE.length]; });
  return colours;
}

function decodeBase64(text) {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return bytes.buffer;
}
function float32Array(text) { return new Float32Array(decodeBase64(text)); }
function uint32Array(text) { return new Uint32Array(decodeBase64(text)); }

function median(values) {
  const sorted = values.filter(v => v !== null && Number.isFinite(v)).sort((a, b) => a - b);
  if (sorted.length === 0) return null;
  const middle = Math.floor(sorted.length / 2);
  return sorted.length % 2 ? sorted[middle] : 0.5 * (sorted[middle - 1] + sorted[middle]);
}

// Plotly with the same look everywhere: the mode bar always visible (zoom, pan, reset, PNG).
const PLOT_CONFIG = {responsive: true, displaylogo: false, displayModeBar: true};
function plot(container, traces, layout) {
  return Plotly.newPlot(container, traces, Object.assign({margin: {l: 60, r: 14, t: 36, b: 50},
    font: {size: 12}, hovermode: "closest"}, layout), PLOT_CONFIG);
}

// A <select> with the given options; onChange(value) also runs once for the initial value.
function selectControl(label, options, onChange) {
  const select = el("select", {onchange: () => onChange(select.value)},
    options.map(option => el("option", {value: option.value, text: option.label})));
  return el("label", {}, [label + " ", select]);
}

// A grid of plots and the <select> that picks what it shows; draw(value, grid) fills the emptied grid.
function selectablePlotGrid(section, label, options, draw) {
  const grid = el("div", {class: "plots"});
  const redraw = value => { grid.replaceChildren(); draw(value, grid); };
  section.appendChild(el("div", {class: "controls"}, [selectControl(label, options, redraw)]));
  section.appendChild(grid);
  redraw(options[0].value);
}

// The page reports its own state for the browser tests (window.arcplanReport.ready etc.).
window.arcplanReport = {ready: false, views: []};
