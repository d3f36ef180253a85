// ESLint for the pages' web code (docs/developer-guide.md, "Web pages"): the recommended rules,
// run by ctest (tests/web/CMakeLists.txt) with the packages package.json pins.
"use strict";
const js = require("@eslint/js");
const globals = require("globals");

module.exports = [
  js.configs.recommended,
  {
    // The pages' scripts: classic scripts in the browser (one page's files share its scope),
    // that also load in Node for their unit tests (the `module` they export to).
    files: ["src/**/web/*.js"],
    languageOptions: {
      ecmaVersion: 2020,
      sourceType: "script",
      globals: { ...globals.browser, module: "readonly" },
    },
  },
  {
    files: ["tests/web/**/*.js", "eslint.config.js"],
    languageOptions: { ecmaVersion: 2022, sourceType: "commonjs", globals: { ...globals.node } },
  },
];
