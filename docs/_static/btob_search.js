// SPDX-License-Identifier: GPL-3.0-or-later
// The search page's summaries: Sphinx's searchtools.js fetches each result's page to quote the words found in it,
// and a browser refuses fetch() to pages opened from disk (file://: a CORS error in the console for every result,
// and no summary anyway).  There the results are listed without summaries; served over HTTP they keep them.
// Loaded after documentation_options.js (Sphinx puts html_js_files after its own scripts); searchtools.js reads
// the flag when it lists each result.
if (window.location.protocol === "file:" && typeof DOCUMENTATION_OPTIONS !== "undefined") {
  DOCUMENTATION_OPTIONS.SHOW_SEARCH_SUMMARY = false;
}
