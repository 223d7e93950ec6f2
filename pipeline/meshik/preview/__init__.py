"""The preview of an output folder: the page, its app and the three.js files it imports, served by
`meshik view`; contact-sheet pictures."""
