// The charts of the HTML report of movseg bench and eval. apps/html_report.cc puts this file,
// Chart.js and the figures (the JSON of #movseg-data) into the page, which so works offline.
// Drawn without animation, so that a printout or a screenshot shows them whole.
(function () {
  "use strict";
  const data = JSON.parse(document.getElementById("movseg-data").textContent);
  const colours = ["#d62728", "#1f77b4", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"];
  const colour = (index) => colours[index % colours.length];
  const jAxis = { min: 0, max: 1, title: { display: true, text: "J" } };
  Chart.defaults.animation = false;

  new Chart(document.getElementById("j-by-sequence"), {
    type: "bar",
    data: {
      labels: data.sequences,
      datasets: data.methods.map((method, index) => ({
        label: method,
        data: data.j[method],
        backgroundColor: colour(index),
      })),
    },
    options: { scales: { y: jAxis } },
  });

  for (const curve of data.curves) {
    new Chart(document.getElementById(curve.canvas), {
      type: "line",
      data: {
        datasets: curve.series.map((series, index) => ({
          label: series.method,
          data: series.points,
          borderColor: colour(index),
          backgroundColor: colour(index),
          borderWidth: 1.5,
          pointRadius: 1.5,
        })),
      },
      options: {
        scales: { x: { type: "linear", title: { display: true, text: "frame" } }, y: jAxis },
      },
    });
  }
  // For the test that renders the page: every chart was made.
  document.body.dataset.charts = String(Object.keys(Chart.instances).length);
})();
