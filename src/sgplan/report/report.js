"use strict";
// Floor switching, the reach-region toggle and hover details. The id rasters hold, per cell, the room
// id and the object id (red = low byte, green, blue = high byte); they are read once through a canvas.
// sgplanFloors(root, entities) wires the floors under root; the report calls it on its own page, the
// live page of `sgplan serve` on the floors it loads (and reads cells with .cellAt on a click and places
// its own marks with .svgXY).
window.sgplanFloors = function (root, entities) {
  const tabs = Array.from(root.querySelectorAll(".floor-tab"));
  const layers = Array.from(root.querySelectorAll(".floor"));
  const tooltip = root.querySelector("#tooltip");

  function showFloor(k) {
    layers.forEach(function (layer) { layer.hidden = layer.dataset.floor !== String(k); });
    tabs.forEach(function (tab) { tab.setAttribute("aria-selected", tab.dataset.floor === String(k) ? "true" : "false"); });
    document.body.dataset.floor = String(k);
  }
  tabs.forEach(function (tab) { tab.addEventListener("click", function () { showFloor(tab.dataset.floor); }); });
  const firstWithPath = tabs.find(function (tab) { return /path cells/.test(tab.textContent); });
  showFloor(firstWithPath ? firstWithPath.dataset.floor : 0);

  const reach = root.querySelector("#show-reach");
  reach.addEventListener("change", function () { document.body.classList.toggle("hide-reach", !reach.checked); });

  function idsOf(img) {
    const canvas = document.createElement("canvas");
    canvas.width = img.naturalWidth;
    canvas.height = img.naturalHeight;
    const context = canvas.getContext("2d", { willReadFrequently: true });
    context.drawImage(img, 0, 0);
    const rgba = context.getImageData(0, 0, canvas.width, canvas.height).data;
    const ids = new Uint32Array(canvas.width * canvas.height);
    for (let i = 0; i < ids.length; i++) {
      ids[i] = rgba[4 * i] | (rgba[4 * i + 1] << 8) | (rgba[4 * i + 2] << 16);
    }
    return ids;
  }
  function whenLoaded(img) {
    return img.complete ? Promise.resolve(img) : new Promise(function (ok) { img.addEventListener("load", function () { ok(img); }); });
  }

  // The map is drawn in the map frame: x (the grid's rows) to the right, y (its columns) upwards; the id
  // rasters are stored the same way, one pixel per cell, cols high and rows wide.
  // The cell under a pointer event on a layer's stage ({row, col, floor, pixel}), or null off the map.
  function cellAt(layer, event) {
    const rows = Number(layer.dataset.rows), cols = Number(layer.dataset.cols);
    const box = layer.querySelector(".stage").getBoundingClientRect();
    const across = Math.floor((event.clientX - box.left) / box.width * rows);
    const down = Math.floor((event.clientY - box.top) / box.height * cols);
    if (across < 0 || down < 0 || across >= rows || down >= cols) { return null; }
    return { row: across, col: cols - 1 - down, floor: Number(layer.dataset.floor), pixel: down * rows + across };
  }
  // A cell's SVG coordinates on its layer's overlays (the inverse of cellAt).
  function svgXY(layer, row, col) {
    return { x: row, y: Number(layer.dataset.cols) - 1 - col };
  }

  layers.forEach(function (layer) {
    const origin = layer.dataset.origin.split(" ").map(Number), resolution = layer.dataset.resolution.split(" ").map(Number);
    const stage = layer.querySelector(".stage");
    let rooms = null, objects = null;
    Promise.all([whenLoaded(layer.querySelector("img.ids.rooms")), whenLoaded(layer.querySelector("img.ids.objects"))])
      .then(function (imgs) { rooms = idsOf(imgs[0]); objects = idsOf(imgs[1]); layer.dataset.ready = "true"; });
    stage.addEventListener("mousemove", function (event) {
      if (!rooms) { return; }
      const cell = cellAt(layer, event);
      if (!cell) { tooltip.hidden = true; return; }
      const row = cell.row, col = cell.col, pixel = cell.pixel;
      const x = origin[0] + (row + 0.5) * resolution[0], y = origin[1] + (col + 0.5) * resolution[1];
      const lines = ["x " + x.toFixed(2) + " m, y " + y.toFixed(2) + " m (row " + row + ", column " + col + "), floor " + layer.dataset.floor];
      const room = entities.rooms[rooms[pixel]];
      const object = entities.objects[objects[pixel]];
      if (object) { lines.push("object: " + object.name + " (" + object.key + ", id " + objects[pixel] + ", floor " + object.floor + ")"); }
      if (room) { lines.push("room: " + room.name + " (" + room.key + ", id " + rooms[pixel] + ", floor " + room.floor + ")"); }
      tooltip.textContent = "";
      lines.forEach(function (line) { const div = document.createElement("div"); div.textContent = line; tooltip.appendChild(div); });
      tooltip.style.left = (event.clientX + 14) + "px";
      tooltip.style.top = (event.clientY + 14) + "px";
      tooltip.hidden = false;
    });
    stage.addEventListener("mouseleave", function () { tooltip.hidden = true; });
  });
  return { showFloor: showFloor, cellAt: cellAt, svgXY: svgXY };
};
(function () {
  const data = document.getElementById("sgplan-entities");
  if (data) { window.sgplanFloors(document, JSON.parse(data.textContent)); }
})();
