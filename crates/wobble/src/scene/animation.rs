//! Animation: a camera path through key poses and objects drifting at a constant velocity,
//! on top of the per-frame spin every object already has. A scene file has none (its camera
//! stands still); the built-in scene has one (`scene/default.rs`, docs/animation.md). The
//! renderer is posed frame by frame with `pipeline::Renderer::pose`.

use super::{Camera, Scene};

/// A camera path and object drift over a fixed number of frames.
#[derive(Clone, Debug, PartialEq)]
pub struct Animation {
    /// Frames in one pass of the animation.
    pub frames: u32,
    /// Frames per second at which it is meant to be shown.
    pub fps: u32,
    /// Camera key poses, spread evenly from frame 0 to frame `frames - 1`; the camera moves
    /// between neighbouring keys along a smoothstep (no jump in speed at a key). Empty: the
    /// scene's own camera.
    pub camera: Vec<Camera>,
    /// Per object (index into [`Scene::objects`]): world units added to its position each
    /// frame. Objects not listed stay where they are.
    pub drift: Vec<(usize, [f64; 3])>,
}

/// Frame rate of scenes without an animation (a scene file).
pub const DEFAULT_FPS: u32 = 30;

impl Animation {
    /// No camera path and no drift: the scene as it is, `frames` frames at [`DEFAULT_FPS`].
    pub fn still(frames: u32) -> Animation {
        Animation {
            frames,
            fps: DEFAULT_FPS,
            camera: Vec::new(),
            drift: Vec::new(),
        }
    }

    /// The camera at `frame`: between the two keys around it, or the scene's `base` camera
    /// without keys. Frames past the end hold the last key.
    pub fn camera_at(&self, base: &Camera, frame: u32) -> Camera {
        let (Some(first), Some(last)) = (self.camera.first(), self.camera.last()) else {
            return *base;
        };
        let spans = self.camera.len() - 1;
        if spans == 0 || self.frames < 2 {
            return *first;
        }
        let t = (f64::from(frame) / f64::from(self.frames - 1)).min(1.0) * spans as f64;
        let k = (t.floor() as usize).min(spans - 1);
        let (Some(a), Some(b)) = (self.camera.get(k), self.camera.get(k + 1)) else {
            return *last;
        };
        let s = (t - k as f64).clamp(0.0, 1.0);
        let s = s * s * (3.0 - 2.0 * s);
        let mix = |x: [f64; 3], y: [f64; 3]| std::array::from_fn(|i| x[i] + (y[i] - x[i]) * s);
        Camera {
            position: mix(a.position, b.position),
            rotation: mix(a.rotation, b.rotation),
            h: a.h,
        }
    }

    /// Object `object`'s position at `frame`, from its position at frame 0.
    pub fn position_at(&self, object: usize, start: [f64; 3], frame: u32) -> [f64; 3] {
        let f = f64::from(frame);
        self.drift
            .iter()
            .filter(|(o, _)| *o == object)
            .fold(start, |p, (_, v)| std::array::from_fn(|i| p[i] + v[i] * f))
    }

    /// The scene posed at `frame`: camera and object positions moved (spin stays with the
    /// frame number, as the pipeline and the reference renderer apply it).
    pub fn scene_at(&self, scene: &Scene, frame: u32) -> Scene {
        let mut s = scene.clone();
        s.camera = self.camera_at(&scene.camera, frame);
        for (i, o) in s.objects.iter_mut().enumerate() {
            o.position = self.position_at(i, o.position, frame);
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam(x: f64) -> Camera {
        Camera {
            position: [x, 0.0, 0.0],
            rotation: [0.0, x / 10.0, 0.0],
            h: 300,
        }
    }

    /// Keys are hit exactly at their frames, the path is monotone between them, and frames
    /// past the end hold the last key.
    #[test]
    fn camera_path_hits_keys() {
        let a = Animation {
            frames: 21,
            fps: 30,
            camera: vec![cam(0.0), cam(100.0), cam(50.0)],
            drift: Vec::new(),
        };
        let base = cam(-1.0);
        assert_eq!(a.camera_at(&base, 0), cam(0.0));
        assert_eq!(a.camera_at(&base, 10), cam(100.0));
        assert_eq!(a.camera_at(&base, 20), cam(50.0));
        assert_eq!(a.camera_at(&base, 500), cam(50.0));
        // Frame 2 is a fifth of the way through the first span: smoothstep 3s^2 - 2s^3.
        let q = a.camera_at(&base, 2).position[0];
        let s: f64 = 0.2;
        assert!(
            (q - 100.0 * (3.0 * s * s - 2.0 * s * s * s)).abs() < 1e-9,
            "{q}"
        );
        let xs: Vec<f64> = (0..=10)
            .map(|f| a.camera_at(&base, f).position[0])
            .collect();
        assert!(xs.windows(2).all(|w| w[1] >= w[0]), "{xs:?}");
        assert_eq!(Animation::still(5).camera_at(&base, 3), base);
    }

    #[test]
    fn drift_is_linear_in_frames() {
        let a = Animation {
            drift: vec![(1, [2.0, -0.5, 0.0])],
            ..Animation::still(10)
        };
        assert_eq!(a.position_at(1, [1.0, 1.0, 1.0], 4), [9.0, -1.0, 1.0]);
        assert_eq!(a.position_at(0, [1.0, 1.0, 1.0], 4), [1.0, 1.0, 1.0]);
    }
}
