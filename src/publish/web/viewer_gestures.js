// The published viewer's test mode, its gestures: gestures=wheel,X,Y,DY;drag,X0,Y0,X1,Y1;
// shiftdrag,...;pinch,X,Y,D,S;mode,light;mode,pan;reset (canvas pixels) are played on the
// picture as the browser's own events would come, in order (viewer_ui.js records the view after
// each as data-pixels-gesture-N with data-camera-gesture-N ("zoom x y") and
// data-light-gesture-N ("x y z")). surrogateViewer.gestures(canvas, frame) gives play(step);
// frame() is where the canvas's pixels are on the screen ({ left, top, scale }).
var surrogateViewer = surrogateViewer || {};
surrogateViewer.gestures = function (canvas, frame) {
  "use strict";
  function at(p) {
    var f = frame();
    return { clientX: f.left + p[0] * f.scale, clientY: f.top + p[1] * f.scale };
  }
  function pointer(type, id, p, touch, shift) {
    var c = at(p);
    canvas.dispatchEvent(new PointerEvent(type, { pointerId: id, pointerType: touch ? "touch" : "mouse", isPrimary: id === 1 || id === 11,
      clientX: c.clientX, clientY: c.clientY, buttons: type === "pointerup" ? 0 : 1, shiftKey: !!shift, bubbles: true, cancelable: true }));
  }
  function play(step) {
    var a = step.split(","), v = a.slice(1).map(Number);
    if (a[0] === "wheel") {
      var c = at([v[0], v[1]]);
      canvas.dispatchEvent(new WheelEvent("wheel", { clientX: c.clientX, clientY: c.clientY, deltaY: v[2], deltaMode: 0, bubbles: true, cancelable: true }));
    } else if (a[0] === "drag" || a[0] === "shiftdrag") {
      var shift = a[0] === "shiftdrag";
      pointer("pointerdown", 1, [v[0], v[1]], false, shift);
      pointer("pointermove", 1, [(v[0] + v[2]) / 2, (v[1] + v[3]) / 2], false, shift);
      pointer("pointermove", 1, [v[2], v[3]], false, shift);
      pointer("pointerup", 1, [v[2], v[3]], false, shift);
    } else if (a[0] === "mode") {
      document.querySelector("#tools button[data-drag=" + (a[1] === "light" ? "light" : "pan") + "]").click();
    } else if (a[0] === "pinch") {
      var d = v[2], s = v[3];
      pointer("pointerdown", 11, [v[0] - d, v[1]], true);
      pointer("pointerdown", 12, [v[0] + d, v[1]], true);
      pointer("pointermove", 11, [v[0] - d * s, v[1]], true);
      pointer("pointermove", 12, [v[0] + d * s, v[1]], true);
      pointer("pointerup", 11, [v[0] - d * s, v[1]], true);
      pointer("pointerup", 12, [v[0] + d * s, v[1]], true);
    } else if (a[0] === "reset") {
      document.getElementById("reset").click();
    } else {
      throw new Error("unknown test gesture " + a[0]);
    }
  }
  return play;
};
