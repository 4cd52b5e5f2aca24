// expect: the character '`'
`touch x`;
