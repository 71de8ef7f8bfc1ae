//! A disk's life at its track, whatever the track is: it rolls until it loses contact (or
//! stops, leaves the track, or the run ends), flies until it touches the track again (or
//! passes its end, or the run ends), and where it touches, the impact decides: it rolls on,
//! bounces into another flight, lifts off again at once, or stops. The rigid curve's run and
//! the beam's run drive this one machine; each says how its track rolls, flies and lands a
//! disk ([`Track`]), the beam sharing the impulse with its own unknowns in `coupling`.

use crate::error::Error;

/// What a disk does next, and from where.
pub enum Next<T: Track + ?Sized> {
    /// It rolls from this state.
    Rolls(T::Rolling),
    /// It has left the track here and flies.
    Flies(T::Launch),
    /// A flight has touched the track here.
    Touches(T::Touch),
    /// The run's riding is over: the run ended, a stop, or the disk left the track.
    Ends(T::End),
}

/// A track as a disk's life meets it.
pub trait Track {
    /// Where a disk starts rolling.
    type Rolling;
    /// Where, and how, it leaves the track.
    type Launch;
    /// Where a flight touches the track again.
    type Touch;
    /// What the riding left at its end.
    type End;

    /// Roll from `from` until the disk lifts off, stops, leaves the track, or the run ends.
    fn roll(&mut self, from: Self::Rolling) -> Result<Next<Self>, Error>;

    /// Fly from `launch` until the disk touches the track, passes its end, or the run ends.
    fn fly(&mut self, launch: Self::Launch) -> Result<Next<Self>, Error>;

    /// The impact where a flight touched the track, and what follows it.
    fn land(&mut self, touch: Self::Touch) -> Result<Next<Self>, Error>;
}

/// Drive the disk from `start` through its phases until its riding ends.
pub fn live<T: Track>(track: &mut T, start: Next<T>) -> Result<T::End, Error> {
    let mut next = start;
    loop {
        next = match next {
            Next::Rolls(from) => track.roll(from)?,
            Next::Flies(launch) => track.fly(launch)?,
            Next::Touches(touch) => track.land(touch)?,
            Next::Ends(end) => return Ok(end),
        };
    }
}
