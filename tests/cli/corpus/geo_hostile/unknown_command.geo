// expect: 'Background' is a command Stentor does not know
Background Mesh View[0];
