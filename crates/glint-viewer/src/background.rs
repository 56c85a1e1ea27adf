//! The window's background: the frame's clear colour, not panel fills.
//!
//! egui draws a panel's fill as a textured quad over the panel's whole area, and on a software
//! rasterizer (lavapipe) every such pixel costs as much as an image's: the menu, status, side
//! and central panels' fills were one textured layer over the whole window, about two thirds of
//! the UI frame's rasterization. A clear is a fast path there. So the panels are transparent
//! and the clear colour is the theme's panel colour, the view's background included.
//!
//! Measured with `glint view whitted --width 960 --height 540 --benchmark-drag 10`, fills on
//! and off alternated in one run (2026-12-03): 12.7, 13.1 → 20.2, 19.1 UI frames/s; the
//! rasterizer threads' share of the CPU fell from 51 % to 24 %, 82 → 25 ms of CPU a frame.

use egui::{Color32, Visuals};

/// The colour behind every panel and the view, for `visuals`' theme (the panels' own fill
/// colour before `unfill_panels`).
pub fn background(visuals: &Visuals) -> Color32 {
    if visuals.dark_mode { Visuals::dark().panel_fill } else { Visuals::light().panel_fill }
}

/// Makes every panel of both themes transparent: the clear colour (`background`) shows.
pub fn unfill_panels(ctx: &egui::Context) {
    ctx.all_styles_mut(|style| style.visuals.panel_fill = Color32::TRANSPARENT);
}

/// `image` (premultiplied RGBA, as egui renders it) over `background`, opaque: what a window
/// cleared to `background` shows, for renderers that clear to transparent (egui_kittest).
pub fn over_background(image: &mut [u8], background: Color32) {
    let bg = background.to_array();
    for px in image.chunks_exact_mut(4) {
        let keep = 255 - u32::from(px[3]);
        for c in 0..3 {
            px[c] = (u32::from(px[c]) + (u32::from(bg[c]) * keep + 127) / 255).min(255) as u8;
        }
        px[3] = 255;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transparent_shows_the_background_and_opaque_hides_it() {
        let mut px = [0, 0, 0, 0, 10, 20, 30, 255, 50, 0, 0, 128];
        over_background(&mut px, Color32::from_rgb(200, 100, 40));
        assert_eq!(px, [200, 100, 40, 255, 10, 20, 30, 255, 50 + 100, 50, 20, 255]);
    }

    #[test]
    fn the_dark_background_is_the_dark_panel_colour() {
        assert_eq!(background(&Visuals::dark()), Visuals::dark().panel_fill);
        assert_eq!(background(&Visuals::light()), Visuals::light().panel_fill);
        assert_ne!(background(&Visuals::dark()), Color32::TRANSPARENT);
    }
}
