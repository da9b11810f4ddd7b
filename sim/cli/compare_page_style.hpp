// The constant style sheet and script of the compare page (compare_page.cpp), inline in it so
// that the page needs nothing but its own folder.
#pragma once

namespace bimloc::cli {

// The page's CSS: system fonts, one column of at most 1100 px, tables with figures aligned.
extern const char* const kComparePageStyle;

// The page's script: on load, every picture's file is fetched once more (the thumbnails load
// lazily) and body's data-images set to "LOADED/TOTAL", which the browser test reads; and the
// run a link points to is unfolded.
extern const char* const kComparePageScript;

}  // namespace bimloc::cli
