"""The browser view's page: view.html, view.css and view.js, served by
btplan.monitor.browser. No library and no network: the page draws the tree itself."""
