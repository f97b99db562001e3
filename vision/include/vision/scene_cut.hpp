#pragma once
// SceneCut: tells when the whole view changed at once (another scene in a recording, the room's
// lights switched on, the camera knocked), from the motion stage's foreground count. The face
// tracks then describe a picture that is gone: followed onto the new one, a track's corners land
// on whatever is there and its box carries a hat over an eye or the background for the grace
// frames. A cut is the foreground jumping from one frame to the next; a person walking in, or a
// card moved away from where the background model learnt it, grows it over several frames.

namespace vision {

class SceneCut {
public:
    /// Least foreground fraction after a cut, and least jump from the frame before. Measured on
    /// the demo video (opencv-doc's Megamind.avi): its two cuts jump 0.20 -> 0.44 and to 0.41;
    /// the card leaving the centre after training ramps to 0.59 by at most 0.08 a frame; FGNet's
    /// talking face (close to the camera, 1000 frames) never passes 0.29.
    static constexpr float kMinFraction = 0.35f;
    static constexpr float kMinJump = 0.15f;
    /// Frames after start-up (or reset()) that are never a cut: a motion model that has seen only
    /// a frame or two marks noise as motion (the demo video's second frame: 0.4).
    static constexpr int kWarmUpFrames = 5;

    /// The frame's foreground pixels out of `pixels`; true when this frame is a cut.
    bool update(int foregroundPixels, int pixels) noexcept;
    /// Starts again as at start-up (after a gap in the frames, or the motion model restarted).
    void reset() noexcept
    {
        previous_ = -1.f;
        frames_ = 0;
    }

private:
    float previous_ = -1.f;  // the last frame's fraction; < 0: none
    int frames_ = 0;         // frames seen since start-up or reset(), up to kWarmUpFrames
};

}  // namespace vision
