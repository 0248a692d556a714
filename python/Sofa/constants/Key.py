"""Keys as the one-character strings of event["key"]: the arrows are characters 18 to 21 (what the
viewer sends), letters are upper case, KP_0 .. KP_9 the digits."""

leftarrow = chr(18)
uparrow = chr(19)
rightarrow = chr(20)
downarrow = chr(21)
space = " "
plus = "+"
minus = "-"

for _code in range(ord("A"), ord("Z") + 1):
    globals()[chr(_code)] = chr(_code)
for _digit in range(10):
    globals()[f"KP_{_digit}"] = chr(ord("0") + _digit)
del _code, _digit
